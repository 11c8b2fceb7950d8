% nis17 (issue 37): `when/3` as a neutral situation's next situation, its
% branches only building values: a comparison (`>`, the evaluator's error
% on a non-number) choosing a compound or the next step, `==` choosing an
% atom situation.
diag_mod(seek(Limit, Mark, Xs),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => step(Xs) ]
    ],
    [ id ==> step([]),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> step([X|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => apply(when(_, _, _), [X == Mark, marked, over(X, Rest)]) ]
    ],
    [ id ==> over(X, Rest),
      type ==> neutral,
      arcs ==> [ empty : empty => apply(when(_, _, _), [X > Limit, found(X), step(Rest)]) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> marked, type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
