% A counter loop that type inference types: `n` and `N` are native ints in
% generated code. The allocation test stops it from its Actions.
diag_mod(main,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N)] => (N >= 1000000000 -> fs ; otherwise -> is) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).
