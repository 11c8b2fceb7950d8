% Helper review19 (issue 37, shape c): N calls of an embedded DM, the limit
% the recursive situation's in_arg; the callee hands the pipe back with
% `out_arg ==> X` and ends in a final carrying a compound, `done(X, tick)`,
% which the caller's exit arc destructures (`done(K, tick)`: the count
% compared with `K`).
diag_mod(relay,
  [ [ id ==> call,
      type ==> recursive,
      in_arg ==> _Limit,
      embedded_dm ==> meter,
      arcs ==> [ done(K, tick) : [inc(calls, N)] => (N >= K -> stop ; otherwise -> call),
                 done(_, _) : empty => odd ]
    ],
    [ id ==> stop, type ==> final ],
    [ id ==> odd, type ==> final ]
  ],
  [ calls ==> 0 ]
).

diag_mod(meter,
  [ [ id ==> read,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => done(X, tick) ]
    ],
    [ id ==> done(_K, _T), type ==> final ]
  ],
  []
).
