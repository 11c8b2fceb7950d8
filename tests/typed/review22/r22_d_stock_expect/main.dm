% Helper review22 (issue 37, shape d): a walk of pairs `Name-Qty` whose
% comparison is an exit arc's expectation: each pair is handed to
% `key_of`, which ends in `key(Name)`, and `key(Want)` (the target, by
% unification) comes before the catch-all `key(_)`.
diag_mod(inventory(Rounds, Stock, Want),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> lookup(Stock, Want),
      arcs ==> [ found(_) : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask),
                 not_found : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask) ]
    ],
    [ id ==> closed, type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(lookup(Stock, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Stock) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> try([P|Ps]),
      type ==> recursive,
      embedded_dm ==> key_of(P),
      arcs ==> [ key(Want) : empty => found(P),
                 key(_) : empty => try(Ps) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).

diag_mod(key_of(K-_Qty),
  [ [ id ==> split,
      type ==> neutral,
      arcs ==> [ empty : empty => key(K) ]
    ],
    [ id ==> key(_), type ==> final ]
  ],
  []
).
