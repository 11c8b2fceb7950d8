% Shape (d): the list built before the walk: the dock appended to the
% places (`append(Places, [Dock], All)`) in the first arc, carried in the
% caller's id `round(I, All)`; the walk looks for the dock (last).
diag_mod(route(Rounds, Places, Dock),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : [append(Places, [Dock], All)] => round(0, All) ] ],
    [ id ==> round(I, All),
      type ==> recursive,
      embedded_dm ==> seek(All, Dock),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J, All) ; otherwise -> stop),
                 not_found : [J is I + 1] => (J < Rounds -> round(J, All) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(seek(L, Goal),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(L) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> walk([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Goal -> found(P) ; otherwise -> walk(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
