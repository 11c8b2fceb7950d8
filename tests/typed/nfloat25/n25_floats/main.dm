% Helper nfloat25 (issue 37): pairs of numbers compared and computed on by
% plain Prolog functions (`cmp/2` in a condition, `pick/3` selecting the
% next situation, `calc/2` and `same/2` said); `loc/2` compares each
% number with a local read by `get` and passes atoms that name a local.
diag_mod(fl(Pairs),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => walk(Pairs) ]
    ],
    [ id ==> walk([]), type ==> final ],
    [ id ==> walk([X-Y|Ps]),
      type ==> neutral,
      arcs ==> [ empty : [say(apply(calc(_, _), [X, Y])), say(apply(same(_, _), [X, Y]))] =>
                   (apply(cmp(_, _), [X, Y]) == lt -> walk(Ps) ; otherwise -> apply(pick(_, _, _), [X, Y, Ps])) ]
    ],
    [ id ==> skip(Ps),
      type ==> neutral,
      arcs ==> [ empty : say(skipped) => walk(Ps) ]
    ]
  ],
  []
).

diag_mod(ints(X, Y),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : say(apply(idiv(_, _), [X, Y])) => apply(step(_), [X]) ]
    ],
    [ id ==> at(_), type ==> final ]
  ],
  []
).

diag_mod(loc(Xs, T),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : set(lim, T) => go(Xs) ]
    ],
    [ id ==> go([]), type ==> final ],
    [ id ==> go([X|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(cmp(_, _), [X, get(lim, _)]) == lt -> go(Rest) ; otherwise -> named(X, Rest)) ]
    ],
    [ id ==> named(X, Rest),
      type ==> neutral,
      arcs ==> [ empty : say(X) =>
                   (apply(same(_, _), [X, lim]) == yes -> go(Rest) ; otherwise -> apply(root(_), [X])) ]
    ],
    [ id ==> done(_), type ==> final ]
  ],
  [ lim ==> 0.5 ]
).
