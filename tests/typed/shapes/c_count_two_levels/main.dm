% Shape (c): the count handed back through two embedded levels in final
% ids: `relay` calls `outer(N)`, which calls `inner(N)`; `inner` counts
% (`M is N + 1`) and ends in `done(M)`, `outer`'s exit arc matches it and
% ends in `back(M)`, which `relay`'s exit arc matches and compares with
% its limit. `relay(Max)` makes Max calls (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => call(0) ] ],
    [ id ==> call(N),
      type ==> recursive,
      embedded_dm ==> outer(N),
      arcs ==> [ back(M) : empty => (M < Max -> call(M) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(outer(N),
  [ [ id ==> ask, type ==> recursive, embedded_dm ==> inner(N),
      arcs ==> [ done(M) : empty => back(M) ] ],
    [ id ==> back(M), type ==> final ]
  ],
  []
).

diag_mod(inner(N),
  [ [ id ==> step, type ==> neutral, arcs ==> [ empty : [M is N + 1] => done(M) ] ],
    [ id ==> done(M), type ==> final ]
  ],
  []
).
