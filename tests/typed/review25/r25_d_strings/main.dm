% Helper review25 (issue 37, shape d): strings as elements (`"tea"`, code
% lists as the original reads them), walked for the one equal to the
% wanted string; the rounds counted in the caller's id, the string found
% handed back in the final's id.
diag_mod(shop(Rounds, Goods, Want),
  [ [ id ==> enter,
      type ==> neutral,
      arcs ==> [ empty : empty => aisle(0) ]
    ],
    [ id ==> aisle(I),
      type ==> recursive,
      embedded_dm ==> shelf(Goods, Want),
      arcs ==> [ got(_S) : [J is I + 1] => (J >= Rounds -> till ; otherwise -> aisle(J)),
                 none : [J is I + 1] => (J >= Rounds -> till ; otherwise -> aisle(J)) ]
    ],
    [ id ==> till, type ==> final ]
  ],
  []
).

diag_mod(shelf(Goods, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => scan(Goods) ]
    ],
    [ id ==> scan([]),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> scan([G|Gs]),
      type ==> neutral,
      arcs ==> [ empty : empty => (G == Want -> got(G) ; otherwise -> scan(Gs)) ]
    ],
    [ id ==> got(_), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(groceries,
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> shop(2, ["tea", "milk", "bread"], "milk"),
      arcs ==> [ till : empty => fin ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  []
).
