% Workload (c) of issue 37: N calls of an embedded DM, the limit as the
% recursive situation's in_arg, the callee handing its pipe back with
% `out_arg ==> X` (X its own in_arg). `main` with in_arg N makes N calls,
% 3 transitions each, plus the final situation.
diag_mod(main,
  [ [ id ==> call,
      type ==> recursive,
      in_arg ==> Limit,
      embedded_dm ==> echo,
      arcs ==> [ back : [inc(n, N)] => (N >= Limit -> fs ; otherwise -> call) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(echo,
  [ [ id ==> is,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => back ]
    ],
    [ id ==> back, type ==> final ]
  ],
  []
).
