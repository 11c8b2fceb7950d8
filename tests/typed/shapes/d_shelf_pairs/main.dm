% Shape (d) over pairs `Item-Shelf`: the walk `check([I-S|More])` compares
% the item with the wanted one and ends in `on(S)` (the shelf) or `none`;
% rounds in the caller's id.
diag_mod(stock(Rounds, Pairs, Item),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      embedded_dm ==> where(Pairs, Item),
      arcs ==> [ on(S) : [J is I + 1] => (J < Rounds -> ask(J) ; otherwise -> done),
                 none : [J is I + 1] => (J < Rounds -> ask(J) ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(where(Pairs, Item),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => check(Pairs) ] ],
    [ id ==> check([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> check([I-S|More]),
      type ==> neutral,
      arcs ==> [ empty : empty => (I == Item -> on(S) ; otherwise -> check(More)) ]
    ],
    [ id ==> on(S), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
