% review17 (issue 37, shape c): three DMs deep. `mission(Trips)` puts the
% number of trips in the pipe; `go` receives it as its in_arg and calls a
% courier, which calls a handoff that hands the pipe back (in_arg P,
% out_arg P); the trips done are a global. 5 transitions a trip.
diag_mod(mission(Trips),
  [ [ id ==> brief,
      type ==> neutral,
      out_arg ==> Trips,
      arcs ==> [ empty : empty => go ]
    ],
    [ id ==> go,
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> courier,
      arcs ==> [ delivered : [inc(trips_done, T)] => (T >= Lim -> rest ; otherwise -> go),
                 lost : empty => rest ]
    ],
    [ id ==> rest, type ==> final ]
  ],
  []
).

diag_mod(courier,
  [ [ id ==> leave,
      type ==> recursive,
      embedded_dm ==> handoff,
      arcs ==> [ passed : empty => delivered,
                 dropped : empty => lost ]
    ],
    [ id ==> delivered, type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  []
).

diag_mod(handoff,
  [ [ id ==> give,
      type ==> neutral,
      in_arg ==> Parcel,
      out_arg ==> Parcel,
      arcs ==> [ empty : empty => passed ]
    ],
    [ id ==> passed, type ==> final ],
    [ id ==> dropped, type ==> final ]
  ],
  []
).
