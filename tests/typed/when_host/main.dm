% `when/3` registered by the host in Rust (declared in host_functions.pl):
% it replaces the runtime's, so the compiler keeps the evaluator's call.
diag_mod(main(X),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X == a, here, elsewhere]),
      arcs ==> [ empty : [say(apply(when(_, _, _), [X == a, yes, no]))]
                   => apply(when(_, _, _), [X == a, fin(x), fin(y)]) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).
