% Shape (d): the final hands back the place and the rest of the list,
% `found(P, Rest)`, which the caller's exit arc matches; `not_found`;
% rounds in a local compared with `>`.
diag_mod(visit(Rounds, Places, Target),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> find(Places, Target),
      arcs ==> [ found(P, Rest) : [inc(n, N)] => (Rounds > N -> round ; otherwise -> stop),
                 not_found : [inc(n, N)] => (Rounds > N -> round ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(find(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => next(Places) ] ],
    [ id ==> next([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> next([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P, Ps) ; otherwise -> next(Ps)) ]
    ],
    [ id ==> found(P, Rest), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
