% Shape (d) with an arithmetic `when/3`: the walk `try([X|Xs])` over a list
% of integers hands back through the pipe, at every element, whether it is
% above the limit: `apply(when(_, _, _), [X > Limit, found(X), none])` (the
% runtime's `when/3`, a branch built from the element). The caller's run
% ends with the last element's answer in the pipe.
diag_mod(hunt(Rounds, Items, Limit),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> search(Items, Limit),
      arcs ==> [ done : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> fin) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

diag_mod(search(Items, Limit),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Items) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => done ] ],
    [ id ==> try([X|Xs]),
      type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X > Limit, found(X), none]),
      arcs ==> [ empty : empty => try(Xs) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).
