% Shape (d): the target in the walk's id under the name of the searching
% DM's parameter (`seek(L, T)`, `walk([P|Ps], T)`: the id shares a variable
% with the DM's head, so the walk only matches while T is the target).
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

diag_mod(seek(L, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(L, T) ] ],
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
