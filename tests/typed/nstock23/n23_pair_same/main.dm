% Helper nstock23 (issue 37): a callee whose head is a compound with a
% constant inside, `same(p(A, B, on))`, deciding by a condition on the
% pattern's two variables which final it reaches; the walker counts the
% pairs that agree in a local. An element `p(X, Y, off)` does not match
% the head: the call is an error (E13), in both back ends alike.
diag_mod(agree(Pairs),
  [ [ id ==> walk(Pairs),
      type ==> neutral,
      arcs ==> [ empty : empty => step(Pairs) ]
    ],
    [ id ==> step([]),
      type ==> neutral,
      arcs ==> [ empty : [get(hits, H)] => done(H) ]
    ],
    [ id ==> step([Q|Qs]),
      type ==> recursive,
      embedded_dm ==> same(Q),
      arcs ==> [ yes : [inc(hits, _)] => step(Qs),
                 no : empty => step(Qs) ]
    ],
    [ id ==> done(_), type ==> final ]
  ],
  [ hits ==> 0 ]
).

diag_mod(same(p(A, B, on)),
  [ [ id ==> test,
      type ==> neutral,
      arcs ==> [ empty : empty => (A == B -> yes ; otherwise -> no) ]
    ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).
