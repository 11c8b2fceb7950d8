% A battery check on a level nothing reads (the engineer forgot get/2).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(checking) => (Level > 20 -> fs ; otherwise -> charge) ] ],
    [ id ==> charge, type ==> neutral, arcs ==> [ empty : say(charging) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ level ==> 50 ]).
