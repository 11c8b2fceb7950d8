% The neutral counter loop with its limit as in_arg: `main` with in_arg Max
% makes Max + 1 transitions (the workload a of issue 28).
diag_mod(main,
  [ [ id ==> is,
      type ==> neutral,
      in_arg ==> Max,
      arcs ==> [ empty : [inc(n, N)] => (N >= Max -> fs ; otherwise -> is) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).
