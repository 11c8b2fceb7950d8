% Shape (d): the searching DM's first situation is named by its list
% parameter (`try(L)` in DM `walk(L, T)`, D-7), then walks `step([P|Ps])`
% comparing each place with the target; `found(P)` or `not_found`.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> walk(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(walk(L, T),
  [ [ id ==> try(L), type ==> neutral, arcs ==> [ empty : empty => step(L) ] ],
    [ id ==> step([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> step([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == T -> found(P) ; otherwise -> step(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
