% Shape (d): the list from the knowledge base (`class_extension`), asked
% once and passed to each round's call; the walk compares by `==`.
diag_mod(stock(Times),
  [ [ id ==> ask, type ==> neutral,
      arcs ==> [ empty : empty => round(apply(class_extension(_), [drink])) ] ],
    [ id ==> round(Things),
      type ==> recursive,
      embedded_dm ==> pick(Things, milk),
      arcs ==> [ picked(T) : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round(Things)),
                 none : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round(Things)) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(pick(Things, Want),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => at(Things) ] ],
    [ id ==> at([T|Ts]), type ==> neutral,
      arcs ==> [ empty : empty => (T == Want -> picked(T) ; otherwise -> at(Ts)) ] ],
    [ id ==> at([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> picked(T), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
