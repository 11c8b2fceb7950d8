% Helper nstock25 (issue 37): a walker whose exit arcs read three of its
% DM's parameters (`Want` in an expectation, `Limit` in a condition,
% `Tag` in the next situation) while its recursive situation waits for
% `qty_of`: the waiting variant keeps no copy of them, the frame's are
% read after the call.
diag_mod(shelf(Rounds, Stock, Want, Tag, Limit),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> look(Stock, Want, Tag, Limit),
      arcs ==> [ seen(P, T) : [inc(asked, A)] => (A >= Rounds -> closed(P, T) ; otherwise -> ask),
                 none(T) : [inc(asked, A)] => (A >= Rounds -> closed(none, T) ; otherwise -> ask) ]
    ],
    [ id ==> closed(_, _), type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(look(Stock, Want, Tag, Limit),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Stock) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => none(Tag) ]
    ],
    [ id ==> try([P|Ps]),
      type ==> recursive,
      embedded_dm ==> qty_of(P),
      arcs ==> [ qty(Want, Q) : empty => (Q >= Limit -> seen(P, Tag) ; otherwise -> try(Ps)),
                 qty(_, _) : empty => try(Ps) ]
    ],
    [ id ==> seen(_, _), type ==> final ],
    [ id ==> none(_), type ==> final ]
  ],
  []
).

diag_mod(qty_of(K-Q),
  [ [ id ==> split,
      type ==> neutral,
      arcs ==> [ empty : empty => qty(K, Q) ]
    ],
    [ id ==> qty(_, _), type ==> final ]
  ],
  []
).
