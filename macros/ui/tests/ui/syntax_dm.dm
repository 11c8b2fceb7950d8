diag_mod(main,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : hello(] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
