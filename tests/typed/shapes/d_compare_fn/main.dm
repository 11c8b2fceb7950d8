% Shape (d): the comparison made by a Prolog user function
% (`apply(same_place(_, _), [P, T]) == yes`), the walk `try([P|Ps])` by the
% compound id, the target the searching DM's parameter.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> search(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(search(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(same_place(_, _), [P, Target]) == yes -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
