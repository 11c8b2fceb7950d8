% An out_arg the evaluator computes (`apply(F, [X])`, `F` the callee's
% parameter) in a callee the caller pushes natively: the pipe set after the
% next situation `back(X)`. `main(twice(_))`: the pipe a list, doubled at
% each call; `main(nofun(_))`: the user function fails (an error located at
% `take`); `main(none)`: not a function.
diag_mod(main(F),
  [ [ id ==> start, type ==> neutral, out_arg ==> 1, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      embedded_dm ==> callee(F),
      arcs ==> [ back(_) : [J is I + 1] => (J < 3 -> ask(J) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> neutral, in_arg ==> P, arcs ==> [ empty : [say(P)] => fin(P) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(callee(F),
  [ [ id ==> take, type ==> neutral, in_arg ==> X, out_arg ==> apply(F, [X]),
      arcs ==> [ empty : empty => back(X) ] ],
    [ id ==> back(_), type ==> final ]
  ],
  []
).
