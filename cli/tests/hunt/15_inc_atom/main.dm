% A counter initialised to `none` and incremented.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(tries, T), say(T)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ tries ==> none ]).
