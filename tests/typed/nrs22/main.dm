% Helper nrs22 (issue 37): plain functions compiled to Rust, called by
% native code: next situations (`cls/1`, `scan/2`, `calc/2`, `wrap/1`), a
% walk over a list (`scan/2`), conditions (`shape/1`, `ratio/2`,
% `never/1`), an out_arg (`pump/1`). `scan/2`'s function gives `empty`,
% which ends the DM whatever its situations are called (one is `empty`).
% `tests/typed/nrs22_other` has the same DMs and other definitions of the
% functions.
diag_mod(cls(N),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => apply(classify(_), [N]) ] ],
    [ id ==> zero, type ==> final ],
    [ id ==> huge(_), type ==> final ],
    [ id ==> third(_), type ==> final ],
    [ id ==> big, type ==> final ],
    [ id ==> small, type ==> final ],
    [ id ==> other, type ==> final ],
    [ id ==> nothing, type ==> final ]
  ],
  []
).

diag_mod(scan(Items, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => apply(pick(_, _), [Items, T]) ] ],
    [ id ==> rest(Xs), type ==> neutral, arcs ==> [ empty : empty => apply(pick(_, _), [Xs, T]) ] ],
    [ id ==> empty, type ==> final ],
    [ id ==> hit(_), type ==> final ],
    [ id ==> second(_), type ==> final ],
    [ id ==> skipped, type ==> final ]
  ],
  []
).

diag_mod(calc(X, Y),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => apply(diff(_, _), [X, Y]) ] ],
    [ id ==> p(_, _), type ==> final ],
    [ id ==> q(_), type ==> final ]
  ],
  []
).

diag_mod(shape(S),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => (apply(area(_), [S]) == 12 -> twelve ; otherwise -> other) ] ],
    [ id ==> twelve, type ==> final ],
    [ id ==> other, type ==> final ]
  ],
  []
).

diag_mod(ratio(X, Y),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => (apply(quot(_, _), [X, Y]) == 3 -> three ; otherwise -> other) ] ],
    [ id ==> three, type ==> final ],
    [ id ==> other, type ==> final ]
  ],
  []
).

diag_mod(never(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => (apply(nope(_), [X]) == yes -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

diag_mod(wrap(X),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => apply(wrapn(_), [X]) ] ],
    [ id ==> n(_), type ==> final ],
    [ id ==> hello, type ==> final ]
  ],
  []
).

diag_mod(pump(Start),
  [ [ id ==> s0, type ==> neutral, out_arg ==> Start, arcs ==> [ empty : empty => a1 ] ],
    [ id ==> a1, type ==> recursive, embedded_dm ==> grower, arcs ==> [ added : empty => a2 ] ],
    [ id ==> a2, type ==> recursive, embedded_dm ==> grower, arcs ==> [ added : empty => got ] ],
    [ id ==> got, type ==> neutral, in_arg ==> V, arcs ==> [ empty : empty => fin(V) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(grower,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(step(_), [X]),
      arcs ==> [ empty : empty => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).
