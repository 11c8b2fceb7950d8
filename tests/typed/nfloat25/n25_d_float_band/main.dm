% Helper nfloat25 (issue 37, shape d): a sweep of float readings for the
% first in a band above a floor, decided by a plain Prolog function
% (`inband/3`: `/`, `>=`, `=<` on floats) whose answer is the next
% situation (`hit(X)` or `scan(Rest)`); the rounds counted by the
% caller's id.
diag_mod(band(Rounds, Xs, Lo),
  [ [ id ==> idle,
      type ==> neutral,
      arcs ==> [ empty : empty => round(0) ]
    ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> sweep(Xs, Lo),
      arcs ==> [ hit(_X) : [J is I + 1] => (J >= Rounds -> halt ; otherwise -> round(J)),
                 miss : [J is I + 1] => (J >= Rounds -> halt ; otherwise -> round(J)) ]
    ],
    [ id ==> halt, type ==> final ]
  ],
  []
).

diag_mod(sweep(Xs, Lo),
  [ [ id ==> open,
      type ==> neutral,
      arcs ==> [ empty : empty => scan(Xs) ]
    ],
    [ id ==> scan([]),
      type ==> neutral,
      arcs ==> [ empty : empty => miss ]
    ],
    [ id ==> scan([X|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => apply(inband(_, _, _), [X, Lo, Rest]) ]
    ],
    [ id ==> hit(_), type ==> final ],
    [ id ==> miss, type ==> final ]
  ],
  []
).
