% Shape (d): the walk by `get`/`set` of a local list (no compound id): the
% list is put in the local at the start, then each visit takes its head.
diag_mod(patrol(Times, Rooms, Goal),
  [ [ id ==> tour,
      type ==> recursive,
      embedded_dm ==> seek(Rooms, Goal),
      arcs ==> [ at(R) : [inc(tours, T)] => (T >= Times -> home ; otherwise -> tour),
                 lost : [inc(tours, T)] => (T >= Times -> home ; otherwise -> tour) ]
    ],
    [ id ==> home, type ==> final ]
  ],
  [ tours ==> 0 ]
).

diag_mod(seek(Rooms, Goal),
  [ [ id ==> load, type ==> neutral, arcs ==> [ empty : [set(todo, Rooms)] => check ] ],
    [ id ==> check, type ==> neutral,
      arcs ==> [ empty : [get(todo, L)] => (L == [] -> lost ; otherwise -> pop) ] ],
    [ id ==> pop, type ==> neutral,
      arcs ==> [ empty : [get(todo, [R|Rs]), set(todo, Rs)] => (R == Goal -> at(R) ; otherwise -> check) ] ],
    [ id ==> at(R), type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  [ todo ==> [] ]
).
