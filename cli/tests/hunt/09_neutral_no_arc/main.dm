% A neutral situation meant to wait for the arm: its only arc expects
% `ready`, which a neutral situation never perceives.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(start) => wait_arm ] ],
    [ id ==> wait_arm, type ==> neutral,
      arcs ==> [ ready : say(arm_ready) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
