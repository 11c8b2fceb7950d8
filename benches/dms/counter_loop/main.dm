% A neutral loop with a local counter: `main(Max)` makes Max + 1 transitions.
diag_mod(main(Max),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N)] => (N >= Max -> fs ; otherwise -> is) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).
