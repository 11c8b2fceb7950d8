% When an out_arg with side effects is evaluated: after the arc's next
% situation (the machine's order). `s`'s out_arg reads `n` after the next
% situation `t(inc(n, _))` counted it (1; before, it would be 0); `t`'s
% out_arg counts it after the next situation `u(get(n, _), V)` read it.
diag_mod(main,
  [ [ id ==> s, type ==> neutral, out_arg ==> get(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(X), type ==> neutral, in_arg ==> V, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => u(X, get(n, _), V) ] ],
    [ id ==> u(X, N, V), type ==> neutral, in_arg ==> W,
      arcs ==> [ empty : [get(n, M)] => fin(X, N, V, W, M) ] ],
    [ id ==> fin(_, _, _, _, _), type ==> final ]
  ],
  [ n ==> 0 ]
).
