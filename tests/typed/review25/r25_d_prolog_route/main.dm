% Helper review25 (issue 37, shape d): the list enters at a boundary, the
% answer of a Prolog user function (`route/1`, the stops without `hall`)
% asked once and kept in the recursive situation's id; each round walks it
% for the target; the caller's exit arcs are tried in order, `at(kitchen)`
% before `at(P)`, and the rounds are counted by `inc` of a local.
diag_mod(errand(Rounds, Stops, Target),
  [ [ id ==> plan,
      type ==> neutral,
      arcs ==> [ empty : empty => round(apply(route(_), [Stops])) ]
    ],
    [ id ==> round(Route),
      type ==> recursive,
      embedded_dm ==> seek(Route, Target),
      arcs ==> [ at(kitchen) : [inc(n, K), inc(cooks, _)] => (K >= Rounds -> home ; otherwise -> round(Route)),
                 at(_P) : [inc(n, K)] => (K >= Rounds -> home ; otherwise -> round(Route)),
                 lost : [inc(n, K)] => (K >= Rounds -> home ; otherwise -> round(Route)) ]
    ],
    [ id ==> home, type ==> final ]
  ],
  [ n ==> 0, cooks ==> 0 ]
).

diag_mod(seek(Route, Target),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => stop(Route) ]
    ],
    [ id ==> stop([]),
      type ==> neutral,
      arcs ==> [ empty : empty => lost ]
    ],
    [ id ==> stop([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> at(P) ; otherwise -> stop(Ps)) ]
    ],
    [ id ==> at(_), type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  []
).
