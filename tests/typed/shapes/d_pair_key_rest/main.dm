% Shape (d): a list of pairs `Place-Distance` matched by `[P-_|Rest]` (the
% distance not read); the place compared with the target, the walking
% DM's parameter; `found(P)` or `not_found`; the caller's rounds in a
% local counted by `inc` and compared with `<`.
diag_mod(tour(Rounds, Pairs, Target),
  [ [ id ==> again,
      type ==> recursive,
      embedded_dm ==> lookup(Pairs, Target),
      arcs ==> [ found(_) : [inc(done, N)] => (N < Rounds -> again ; otherwise -> finish),
                 not_found : [inc(done, N)] => (N < Rounds -> again ; otherwise -> finish) ]
    ],
    [ id ==> finish, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(lookup(Pairs, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => next(Pairs) ] ],
    [ id ==> next([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> next([P-_|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> next(Rest)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
