% Helper nstock23 (issue 37): one callee with a pattern head,
% `price(_Item-Cost)`, called from two places with different kinds of
% argument: the caller's own parameter, then each element of a list (a
% pair, or not: an error, E13); its final `cost(Cost)` carries the
% pattern's second variable, which the caller keeps in its next
% situation's id and compares with each element's by an exit arc.
diag_mod(basket(First, Items),
  [ [ id ==> open,
      type ==> recursive,
      embedded_dm ==> price(First),
      arcs ==> [ cost(C) : empty => add(Items, C) ]
    ],
    [ id ==> add([], _),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> add([I|Is], C),
      type ==> recursive,
      embedded_dm ==> price(I),
      arcs ==> [ cost(C) : empty => same(I),
                 cost(_) : empty => add(Is, C) ]
    ],
    [ id ==> same(_), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(price(_Item-Cost),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : empty => cost(Cost) ]
    ],
    [ id ==> cost(_), type ==> final ]
  ],
  []
).
