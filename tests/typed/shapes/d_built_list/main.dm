% Shape (d): the list of places built by a function once (`reverse`, a
% list function, in the first next situation), then held in the caller's id
% and passed in each call; rounds in a local.
diag_mod(patrol(Rounds, Places, Target),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : empty => ready(reverse(Places, _)) ] ],
    [ id ==> ready(L),
      type ==> recursive,
      embedded_dm ==> search(L, Target),
      arcs ==> [ found(P) : [inc(n, N)] => (N >= Rounds -> stop ; otherwise -> ready(L)),
                 not_found : [inc(n, N)] => (N >= Rounds -> stop ; otherwise -> ready(L)) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(search(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
