% Shape (d): the target travels in the walk's id (`walk([P|Ps], T)`), not
% as the searching DM's parameter; the caller matches `found(P)` and
% `not_found`; rounds counted in the caller's id.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> seek(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(seek(L, Goal),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(L, Goal) ] ],
    [ id ==> walk([], _), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> walk([P|Ps], T),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == T -> found(P) ; otherwise -> walk(Ps, T)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
