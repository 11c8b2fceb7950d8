% Typed and untyped situations in one DM: the frame is written back before
% untyped code reads the locals, and loaded again after it changed them; a
% user function (`poke`, registered by the test) setting a local to an atom
% behind the compiler's back makes the typed path fall back.
diag_mod(main,
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N)] => (N >= 3 -> show ; otherwise -> is) ]
    ],
    [ id ==> show,
      type ==> neutral,
      arcs ==> [ empty : [screen(get(n, _)), set(n, 10), inc(k, _)] => again ]
    ],
    [ id ==> again,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, M)] => (M >= 12 -> sub ; otherwise -> again) ]
    ],
    [ id ==> sub,
      type ==> recursive,
      embedded_dm ==> count(2),
      arcs ==> [ fs : [get(n, V)] => odd ]
    ],
    [ id ==> odd,
      type ==> neutral,
      arcs ==> [ empty : [apply(poke(_), [x])] => back ]
    ],
    [ id ==> back,
      type ==> neutral,
      arcs ==> [ empty : [get(k, K)] => (K >= 2 -> fs ; otherwise -> show2) ]
    ],
    [ id ==> show2,
      type ==> neutral,
      arcs ==> [ empty : [inc(k, _)] => back ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0, k ==> 0 ]
).

diag_mod(count(Max),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(c, C)] => (C >= Max -> fs ; otherwise -> is) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ c ==> 0 ]
).
