% review17 (issue 37, shape d): the rooms are a constant list a `prog`
% stores in a local; the walk reads it in its next situation, counts its
% visits in another local and hands the count back in the final
% situation (`there(Room, Visits)`, `nowhere(Visits)`).
% `tour(Rounds, Goal)`: a round is the call, `load`, a visit a room, the
% final.
diag_mod(tour(Rounds, Goal),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> walk(Goal),
      arcs ==> [ there(_, V) : [inc(laps, L)] => (L >= Rounds -> home ; otherwise -> round),
                 nowhere(V) : [inc(laps, L)] => (L >= Rounds -> home ; otherwise -> round) ]
    ],
    [ id ==> home, type ==> final ]
  ],
  [ laps ==> 0 ]
).

diag_mod(walk(Goal),
  [ [ id ==> load,
      type ==> neutral,
      prog ==> [ set(rooms, [hall, kitchen, pantry, garage, study, bath, attic, cellar]) ],
      arcs ==> [ empty : empty => room(get(rooms, _)) ]
    ],
    [ id ==> room([]),
      type ==> neutral,
      arcs ==> [ empty : empty => nowhere(get(visits, _)) ]
    ],
    [ id ==> room([R|Rs]),
      type ==> neutral,
      arcs ==> [ empty : [inc(visits, V)] => (R == Goal -> there(R, V) ; otherwise -> room(Rs)) ]
    ],
    [ id ==> there(_, _), type ==> final ],
    [ id ==> nowhere(_), type ==> final ]
  ],
  [ rooms ==> [], visits ==> 0 ]
).
