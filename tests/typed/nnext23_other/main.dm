% Helper nnext23 (issue 37): plain functions compiled to Rust whose clauses
% answer compounds, the next situation selected from the answer's parts
% without the compound built. `hop/3` (a walk's next situation): a
% compound of one part (`step(Xs)`), of two (`at(X, Xs)`), a part built
% (`far(X, 3)`, `go(K, Xs)`), an atom (`done`), a failing clause (`stop`),
% an atom and a compound naming no situation (`odd`, `zap(X)`). `next/2`:
% a list head pattern (the tail a part). `kind/1` in a condition (a
% compound is never the constant), `wrap/1` an out_arg's value.
% `tests/typed/nnext23_other` has the same DMs and other definitions.
diag_mod(walk(Places, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => step(Places) ] ],
    [ id ==> step([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> step([X|Xs]), type ==> neutral,
      arcs ==> [ empty : empty => apply(hop(_, _, _), [X, Xs, T]) ] ],
    [ id ==> go(K, Xs), type ==> neutral,
      arcs ==> [ empty : empty => (K > 4 -> step(Xs) ; otherwise -> none) ] ],
    [ id ==> at(_, _), type ==> final ],
    [ id ==> far(_, _), type ==> final ],
    [ id ==> done, type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(scan(Items, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => apply(next(_, _), [Items, T]) ] ],
    [ id ==> more(Xs), type ==> neutral, arcs ==> [ empty : empty => apply(next(_, _), [Xs, T]) ] ],
    [ id ==> at(_, _), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(sort_of(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => (apply(kind(_), [X]) == small -> small ; otherwise -> check) ] ],
    [ id ==> check, type ==> neutral,
      arcs ==> [ empty : empty => (apply(kind(_), [X]) \== big -> other ; otherwise -> big) ] ],
    [ id ==> small, type ==> final ],
    [ id ==> big, type ==> final ],
    [ id ==> other, type ==> final ]
  ],
  []
).

diag_mod(pack(Start),
  [ [ id ==> s0, type ==> neutral, out_arg ==> Start, arcs ==> [ empty : empty => a1 ] ],
    [ id ==> a1, type ==> recursive, embedded_dm ==> wrapper, arcs ==> [ wrapped : empty => got ] ],
    [ id ==> got, type ==> neutral, in_arg ==> V, arcs ==> [ empty : empty => fin(V) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(wrapper,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(wrap(_), [X]),
      arcs ==> [ empty : empty => wrapped ] ],
    [ id ==> wrapped, type ==> final ]
  ],
  []
).
