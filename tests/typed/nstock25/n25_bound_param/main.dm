% Helper nstock25 (issue 37): the walker's parameter `Got` is unbound
% when it starts and bound by its callee's final (`diag_mod ==>
% mark(I, I)`) while the walker waits; its exit arc reads `Got` after
% the call (the frame's parameter, which the binding reached).
diag_mod(fetch(Rounds, Items),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> pick(Items, Got),
      arcs ==> [ picked(X) : [inc(n, A)] => (A >= Rounds -> closed(X, Got) ; otherwise -> go) ]
    ],
    [ id ==> closed(_, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(pick(Items, Got),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => walk(Items) ]
    ],
    [ id ==> walk([]),
      type ==> neutral,
      arcs ==> [ empty : empty => picked(none) ]
    ],
    [ id ==> walk([I|Is]),
      type ==> recursive,
      embedded_dm ==> mark(I, Got),
      arcs ==> [ marked(Got) : empty => picked(Got),
                 skip : empty => walk(Is) ]
    ],
    [ id ==> picked(_), type ==> final ]
  ],
  []
).

diag_mod(mark(I, _Out),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : empty => (I == b -> marked(I) ; otherwise -> skip) ]
    ],
    [ id ==> marked(_), type ==> final, diag_mod ==> mark(I, I) ],
    [ id ==> skip, type ==> final ]
  ],
  []
).
