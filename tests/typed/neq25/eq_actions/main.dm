% Helper neq25 (issue 37): `X = Y` in arcs' actions (D-30: unified, not
% evaluated; a failure is an error). A fresh variable bound to an int, an
% atom, a list, a compound with variables, an expression left unevaluated,
% another fresh variable; `E = V` the other way round; `=` between bound
% values (equal, and not: `1 = 1.0`, atoms, compounds by parts); `=` in a
% neutral situation's arc, in a recursive one's exit arc binding its
% out_arg, and in the arc into a final situation.
diag_mod(binds(A),
  [ [ id ==> s0,
      type ==> neutral,
      arcs ==> [ empty : [X = A, b = Y, L = [X, Y], P = pair(Y, Z), E = A + 1,
                          W = Z, screen(X), screen(Y), screen(L), screen(P),
                          screen(E), screen(W)] => s1(X, L) ]
    ],
    [ id ==> s1(V, Vs),
      type ==> neutral,
      arcs ==> [ empty : [K = s(V), screen(K), screen(Vs)] => (V == 1 -> done ; otherwise -> s2(K)) ]
    ],
    [ id ==> s2(K),
      type ==> neutral,
      arcs ==> [ empty : [Q = K, screen(Q)] => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% `=` between values that are known: equal (passes), or not (an error).
diag_mod(check(A, B),
  [ [ id ==> s0,
      type ==> neutral,
      arcs ==> [ empty : [X = A, X = B, screen(ok(X))] => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% The count in the pipe; the recursive situation's out_arg bound by `=` in
% one exit arc and by `is` in the other; the callee a neutral situation
% whose arc binds the out_arg by `=` and goes to a final one.
diag_mod(loop(Limit),
  [ [ id ==> go,
      type ==> recursive,
      in_arg ==> N,
      out_arg ==> N1,
      embedded_dm ==> step(Limit),
      arcs ==> [ more : [N1 is N + 1] => go,
                 last : [N1 = N, screen(N1)] => stop ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(step(L),
  [ [ id ==> look,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> Y,
      arcs ==> [ empty : [Y = X] => (X < L -> more ; otherwise -> last) ]
    ],
    [ id ==> more, type ==> final ],
    [ id ==> last, type ==> final ]
  ],
  []
).

% `=` in the arc into the final situation, its out_arg a compound of the
% value bound, and the final's id taking it.
diag_mod(wrap(A),
  [ [ id ==> s0,
      type ==> neutral,
      out_arg ==> R,
      arcs ==> [ empty : [V = A, R = got(V)] => fin(V) ]
    ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).
