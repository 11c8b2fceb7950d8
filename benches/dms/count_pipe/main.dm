% Workload of shape (c) of issue 37, not (c) itself: other names, an extra
% parameter and a nested call. `main(Step)` with in_arg N makes N rounds:
% the recursive situation `go` takes the limit as its in_arg and calls
% `relay(Step)`, which calls `bounce`, whose neutral situation hands its
% in_arg back with `out_arg ==> X`; `relay` maps `back` to `passed(Step)`,
% which `main`'s exit arc matches. A round is 5 transitions.
diag_mod(main(Step),
  [ [ id ==> go,
      type ==> recursive,
      in_arg ==> Max,
      embedded_dm ==> relay(Step),
      arcs ==> [ passed(S) : [inc(count, C)] => (C >= Max -> stop ; otherwise -> go) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ count ==> 0 ]
).

diag_mod(relay(Step),
  [ [ id ==> hop,
      type ==> recursive,
      embedded_dm ==> bounce,
      arcs ==> [ back : empty => passed(Step) ]
    ],
    [ id ==> passed(S), type ==> final ]
  ],
  []
).

diag_mod(bounce,
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
