% Helper review22 (issue 37, shape d): a walk of atoms that says each room
% it checks; the comparison in the next situation's condition; rounds
% counted in a local; three exit arcs (`found(R)`, `not_found`, and
% `nothing` for no rooms at all).
diag_mod(patrol(Rounds, Rooms, Lost),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> sweep(Rooms, Lost),
      arcs ==> [ found(_R) : [inc(laps, L)] => (L >= Rounds -> home ; otherwise -> go),
                 not_found : [inc(laps, L)] => (L >= Rounds -> home ; otherwise -> go),
                 nothing : say('no rooms to sweep') => home ]
    ],
    [ id ==> home, type ==> final ]
  ],
  [ laps ==> 0 ]
).

diag_mod(sweep(Rooms, Lost),
  [ [ id ==> enter,
      type ==> neutral,
      arcs ==> [ empty : empty => (Rooms == [] -> nothing ; otherwise -> try(Rooms)) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : say('not here') => not_found ]
    ],
    [ id ==> try([R|Rs]),
      type ==> neutral,
      arcs ==> [ empty : say(['checking', R]) => (R == Lost -> found(R) ; otherwise -> try(Rs)) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ],
    [ id ==> nothing, type ==> final ]
  ],
  []
).
