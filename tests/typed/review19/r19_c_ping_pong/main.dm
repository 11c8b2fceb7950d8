% Helper review19 (issue 37, shape c): a recursion two DMs deep alternating.
% `rally(Rounds, Depth)` calls `ping(Depth)` each round; `ping(D)` calls
% `pong(D)` while D > 0, and `pong(D)` calls `ping(D - 1)`: A calls B calls
% A, down to `ping(0)`, each level ending in `back`.
diag_mod(rally(Rounds, Depth),
  [ [ id ==> serve,
      type ==> recursive,
      embedded_dm ==> ping(Depth),
      arcs ==> [ back : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> serve) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(ping(D),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : empty => (D > 0 -> hit ; otherwise -> back) ]
    ],
    [ id ==> hit,
      type ==> recursive,
      embedded_dm ==> pong(D),
      arcs ==> [ back : empty => back ]
    ],
    [ id ==> back, type ==> final ]
  ],
  []
).

diag_mod(pong(D),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : empty => hit(E is D - 1) ]
    ],
    [ id ==> hit(E),
      type ==> recursive,
      embedded_dm ==> ping(E),
      arcs ==> [ back : empty => back ]
    ],
    [ id ==> back, type ==> final ]
  ],
  []
).
