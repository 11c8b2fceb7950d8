% More ids sharing a DM parameter's variable (D-7), after review: two
% parameters given the same caller variable (`two(A, A)`, linked to
% `d(a, b)`: the second link fails and is undone), a link that unifies part
% of a compound before it fails (`part(f(_, 1))` against `s(f(2, 3))`), an
% id repeating a parameter (`t(M, M)`), and a linked situation whose next
% situation is a Prolog condition (handed to the machine).
diag_mod(main(A),
  [ [ id ==> start,
      type ==> recursive,
      embedded_dm ==> two(A, A),
      arcs ==> [ r(V) : empty => next(V) ]
    ],
    [ id ==> next(V),
      type ==> recursive,
      embedded_dm ==> part(f(_, 1)),
      arcs ==> [ p(W, G) : empty => more(V, W, G) ]
    ],
    [ id ==> more(V, W, G),
      type ==> recursive,
      embedded_dm ==> rep(A, B),
      arcs ==> [ q(T, U) : empty => done(V, W, G, T, U, B) ]
    ],
    [ id ==> done(V, W, G, T, U, B), type ==> final ]
  ],
  []
).

diag_mod(two(X, Y),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => d(a, b) ] ],
    [ id ==> d(X, Y),
      type ==> neutral,
      arcs ==> [ empty : empty => (member(X, [a, c]) -> r(X) ; otherwise -> r(none)) ]
    ],
    [ id ==> r(X), type ==> final ]
  ],
  []
).

diag_mod(part(P),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => s(f(2, 3)) ] ],
    [ id ==> s(P), type ==> neutral, arcs ==> [ empty : empty => p(P, P) ] ],
    [ id ==> p(_Q, P), type ==> final ]
  ],
  []
).

diag_mod(rep(K, M),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => t(K, K) ] ],
    [ id ==> t(M, M), type ==> neutral, arcs ==> [ empty : [say(M)] => q(K, M) ] ],
    [ id ==> q(K, M), type ==> final ]
  ],
  []
).
