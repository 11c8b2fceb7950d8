% Helper nstock23 (issue 37): a callee whose head is a list pattern,
% `first_of([X|_Rest])`, handed each row of a table; its final `got(X)`
% carries the pattern's variable back, and the walker's exit arc
% `got(Want)` takes the row whose first cell is the target.
diag_mod(table(Rows, Want),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => scan(Rows) ]
    ],
    [ id ==> scan([]),
      type ==> neutral,
      arcs ==> [ empty : empty => missing ]
    ],
    [ id ==> scan([R|Rs]),
      type ==> recursive,
      embedded_dm ==> first_of(R),
      arcs ==> [ got(Want) : empty => hit(R),
                 got(_) : empty => scan(Rs) ]
    ],
    [ id ==> hit(_), type ==> final ],
    [ id ==> missing, type ==> final ]
  ],
  []
).

diag_mod(first_of([X|_Rest]),
  [ [ id ==> pick,
      type ==> neutral,
      arcs ==> [ empty : empty => got(X) ]
    ],
    [ id ==> got(_), type ==> final ]
  ],
  []
).
