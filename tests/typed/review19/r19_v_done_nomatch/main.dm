% Helper review19: `r19_c_done_pair` for bad inputs (not a workload): the
% callee's final carries `big` for a pipe above 100, which no exit arc of
% the caller matches (only `done(K, tick)`).
diag_mod(relay,
  [ [ id ==> call,
      type ==> recursive,
      in_arg ==> _Limit,
      embedded_dm ==> meter,
      arcs ==> [ done(K, tick) : [inc(calls, N)] => (N >= K -> stop ; otherwise -> call) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ calls ==> 0 ]
).

diag_mod(meter,
  [ [ id ==> read,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => (X > 100 -> done(X, big) ; otherwise -> done(X, tick)) ]
    ],
    [ id ==> done(_K, _T), type ==> final ]
  ],
  []
).
