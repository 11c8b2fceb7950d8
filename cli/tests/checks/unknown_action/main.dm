% `sya` is a typo of the declared action `say`; `beep` is declared nowhere.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [sya(hello), beep, empty] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
