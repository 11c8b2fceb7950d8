% The runtime's `when/3` (`apply(when(_, _, _), [C, T, E])`: `C`, `T`, `E`
% evaluated in this order, then `T` if `C`'s value is `true`, else `E`)
% with an arithmetic comparison (`<`, `>`, `=<`, `>=`) as its condition and
% branches that are not constants: built from bound variables, with an
% effect (`inc`: both branches evaluated), nested. In an out_arg, an action
% and a next situation. `X` and `Y` may be numbers (true, false), atoms or
% unbound (the comparison's error, blaming it); `=:=`, `@<` and a
% conjunction are called as goals by the runtime's `when/3` (its condition's
% value is the evaluated goal, `true` only for `==`, `<`, ..).
diag_mod(main(X, Y),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X > Y, found(X), none]),
      arcs ==> [ empty : [say(apply(when(_, _, _), [X < Y, lt(X, Y), ge(Y)])),
                          say(apply(when(_, _, _), [X =< 2, [X], Y])),
                          say(apply(when(_, _, _), [X >= Y, inc(n, _), inc(m, _)])),
                          say(get(n, _)), say(get(m, _)),
                          say(apply(when(_, _, _), [X =:= Y, eq, ne])),
                          say(apply(when(_, _, _), [X @< Y, lt, ge])),
                          say(apply(when(_, _, _), [(X > 0, Y > 0), both, notboth]))]
                   => apply(when(_, _, _), [X >= 1, one, other(X)]) ] ],
    [ id ==> one, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : [say(P)]
                   => apply(when(_, _, _), [Y > 1, apply(when(_, _, _), [X > 2, big, mid]), small]) ] ],
    [ id ==> other(Z), type ==> neutral, in_arg ==> P,
      out_arg ==> apply(when(_, _, _), [3 > Z, get(n, _), inc(m, _)]),
      arcs ==> [ empty : [say(P), say(Z)] => small ] ],
    [ id ==> big, type ==> final ],
    [ id ==> mid, type ==> final ],
    [ id ==> small, type ==> neutral, in_arg ==> Q,
      arcs ==> [ empty : [say(Q), say(get(m, _))] => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  [n ==> 0, m ==> 10]
).

% A comparison in a next situation and in the out_arg of the same arc: the
% next situation's is evaluated first (D-18), so its error is the one met.
diag_mod(second(X),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X =< 5, low(X), high]),
      arcs ==> [ empty : empty => apply(when(_, _, _), [X > 1, big, small]) ] ],
    [ id ==> big, type ==> final ],
    [ id ==> small, type ==> final ]
  ],
  []
).
