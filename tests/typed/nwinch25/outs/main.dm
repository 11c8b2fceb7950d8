% Helper nwinch25 (issue 37): a callee's output parameter bound by some of
% its finals only (`pick`: `halt` leaves it), by all (`mark`), by none
% (`lose`); the caller's variable said, compared and passed on after the
% call, and read (unbound) by the arcs of a final that leaves it.
diag_mod(outs(Items),
  [ [ id ==> feed([]), type ==> neutral, arcs ==> [ empty : empty => done ] ],
    [ id ==> feed([X|Xs]),
      type ==> neutral,
      out_arg ==> X,
      arcs ==> [ empty : empty => one(Xs) ]
    ],
    [ id ==> one(Xs),
      type ==> recursive,
      embedded_dm ==> pick(G),
      arcs ==> [ whole(_) : say([whole, G]) => (G > 10 -> two(Xs, big) ; otherwise -> two(Xs, G)),
                 odd : say(G) => two(Xs, G),
                 halt : say(halted) => two(Xs, none) ]
    ],
    [ id ==> two(Xs, P),
      type ==> recursive,
      embedded_dm ==> mark(P, H),
      arcs ==> [ seen : say([seen, H]) => three(Xs),
                 new : say([new, H]) => three(Xs) ]
    ],
    [ id ==> three(Xs),
      type ==> recursive,
      embedded_dm ==> lose(N),
      arcs ==> [ gone : say([gone, N]) => four(Xs) ]
    ],
    [ id ==> four(Xs),
      type ==> recursive,
      embedded_dm ==> pick(K),
      arcs ==> [ halt : say([halt, K]) => feed(Xs),
                 V : say([V, K]) => feed(Xs) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(pick(_Out),
  [ [ id ==> look,
      type ==> neutral,
      in_arg ==> V,
      arcs ==> [ empty : empty => (integer(V) -> whole(V) ; otherwise -> (V == stop -> halt ; otherwise -> odd)) ]
    ],
    [ id ==> whole(N), type ==> final, diag_mod ==> pick(N) ],
    [ id ==> halt, type ==> final ],
    [ id ==> odd, type ==> final, in_arg ==> W, diag_mod ==> pick(W) ]
  ],
  []
).

diag_mod(mark(P, _Seen),
  [ [ id ==> check,
      type ==> neutral,
      arcs ==> [ empty : empty => (P == none -> new ; otherwise -> seen) ]
    ],
    [ id ==> seen, type ==> final, diag_mod ==> mark(P, [P]) ],
    [ id ==> new, type ==> final, diag_mod ==> mark(P, fresh) ]
  ],
  []
).

diag_mod(lose(_Never),
  [ [ id ==> go, type ==> neutral, arcs ==> [ empty : empty => gone ] ],
    [ id ==> gone, type ==> final ]
  ],
  []
).

% A loop of shape (c) on `pick`: the caller counts the integers it is
% handed back, a halt ends it.
diag_mod(loop(Limit),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> pick(G),
      arcs ==> [ whole(_) : [inc(seen, S)] => (S >= Limit -> over ; otherwise -> (G >= Limit -> over ; otherwise -> round)),
                 odd : say(G) => over,
                 halt : say(halted) => over ]
    ],
    [ id ==> over, type ==> final ]
  ],
  [ seen ==> 0 ]
).
