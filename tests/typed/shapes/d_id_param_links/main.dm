% Ids sharing a DM parameter's variable (D-7): a next situation selects the
% first id that unifies with the variable taken as fresh; the variable is
% then unified with the call's argument where they unify (skipped where
% not). `at(K)` is selected by `at(other)` whatever K is; `mark(Y)` binds
% the caller's unbound argument; `hold(K)`, selected by `hold(Z)` with Z
% unbound, binds Z to the parameter; `first(N)` starts its DM.
diag_mod(main(A),
  [ [ id ==> start,
      type ==> recursive,
      embedded_dm ==> lead(A),
      arcs ==> [ second(Q) : empty => go(0) ]
    ],
    [ id ==> go(I),
      type ==> recursive,
      embedded_dm ==> probe(A, X),
      arcs ==> [ got(K, W) : [J is I + 1] => (J < 3 -> go(J) ; otherwise -> done(X, K, W)) ]
    ],
    [ id ==> done(P, K, W), type ==> final ]
  ],
  []
).

diag_mod(lead(N),
  [ [ id ==> first(N), type ==> neutral, arcs ==> [ empty : empty => second(N) ] ],
    [ id ==> second(N), type ==> final ]
  ],
  []
).

diag_mod(probe(K, Y),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => at(other) ] ],
    [ id ==> at(K), type ==> neutral, arcs ==> [ empty : empty => mark(K) ] ],
    [ id ==> mark(Y), type ==> neutral, arcs ==> [ empty : empty => hold(Z) ] ],
    [ id ==> hold(K), type ==> neutral, arcs ==> [ empty : empty => got(K, Y) ] ],
    [ id ==> got(K, Y), type ==> final ]
  ],
  []
).
