% Shape (d): the places compounds `room(Name)` (as a map gives them); the
% walk `go([room(R)|Rs])` takes each name out of its compound, compares it
% with the target (the walking DM's parameter) and ends in
% `inside(room(R))`, which the caller matches with `inside(_)`; `nowhere`;
% rounds in the caller's id.
diag_mod(hunt(Rounds, Rooms, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> find_room(Rooms, Target),
      arcs ==> [ inside(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 nowhere : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(find_room(Rooms, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => go(Rooms) ] ],
    [ id ==> go([room(R)|Rs]),
      type ==> neutral,
      arcs ==> [ empty : empty => (R == Target -> inside(room(R)) ; otherwise -> go(Rs)) ]
    ],
    [ id ==> go([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> inside(Room), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
