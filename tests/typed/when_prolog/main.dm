% `when/3` defined by the application's Prolog (here: always the third
% argument): it replaces the runtime's (`Engine::install`), so the
% compiler keeps the evaluator's call.
diag_mod(main(X),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X == a, here, elsewhere]),
      arcs ==> [ empty : [say(apply(when(_, _, _), [X == a, yes, no]))]
                   => apply(when(_, _, _), [X == a, fin(x), fin(y)]) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).
