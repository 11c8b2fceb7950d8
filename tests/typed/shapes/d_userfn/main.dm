% Shape (d): the list built by a Prolog user function (`rooms`), once,
% held in the caller's id `round(Rooms)` for every round; exit arcs
% `found(P)` and `found(_)`-like `nowhere`.
diag_mod(tour(Times),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty => round(apply(rooms, [])) ] ],
    [ id ==> round(Rooms),
      type ==> recursive,
      embedded_dm ==> where(Rooms, kitchen),
      arcs ==> [ found(_) : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round(Rooms)),
                 nowhere : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round(Rooms)) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(where(Rooms, Goal),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => next(Rooms) ] ],
    [ id ==> next([R|Rs]), type ==> neutral,
      arcs ==> [ empty : empty => (R == Goal -> found(R) ; otherwise -> next(Rs)) ] ],
    [ id ==> next([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> found(R), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
