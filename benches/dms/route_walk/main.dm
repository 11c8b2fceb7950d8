% Workload of shape (d) of issue 37, not (d) itself: other names, ints
% instead of atoms, an extra parameter and a nested call. `main(Trips,
% Stops, Goal, Tag)` makes `Trips` trips; a trip calls `route(Stops, Goal,
% Tag)`, which calls `walk(Stops, Goal)`: the list of ints walked by the
% compound id `visit([S|Ss])`, ending in `at(S)` or `gone`, which `route`'s
% exit arcs map to `reached(S, Tag)` or `lost(Tag)`, which `main`'s exit
% arcs match. With the goal last of 8 stops, a trip is 13 transitions.
diag_mod(main(Trips, Stops, Goal, Tag),
  [ [ id ==> trip,
      type ==> recursive,
      embedded_dm ==> route(Stops, Goal, Tag),
      arcs ==> [ reached(S, T) : [inc(k, K)] => (K >= Trips -> done ; otherwise -> trip),
                 lost(T) : [inc(k, K)] => (K >= Trips -> done ; otherwise -> trip) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(route(Stops, Goal, Tag),
  [ [ id ==> start,
      type ==> recursive,
      embedded_dm ==> walk(Stops, Goal),
      arcs ==> [ at(S) : empty => reached(S, Tag),
                 gone : empty => lost(Tag) ]
    ],
    [ id ==> reached(S, T), type ==> final ],
    [ id ==> lost(T), type ==> final ]
  ],
  []
).

diag_mod(walk(Stops, Goal),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Stops) ]
    ],
    [ id ==> visit([]),
      type ==> neutral,
      arcs ==> [ empty : empty => gone ]
    ],
    [ id ==> visit([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == Goal -> at(S) ; otherwise -> visit(Ss)) ]
    ],
    [ id ==> at(S), type ==> final ],
    [ id ==> gone, type ==> final ]
  ],
  []
).
