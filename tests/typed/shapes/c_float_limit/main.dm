% Shape (c): the limit a float (`relay(300.0)`), the count an int in the
% caller's id compared with it by `<`; the limit the recursive situation's
% in_arg, handed back by the callee's `out_arg ==> X`.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> Max, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> mirror,
      arcs ==> [ back : [J is I + 1] => (J < Lim -> ask(J) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(mirror,
  [ [ id ==> take, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => back ] ],
    [ id ==> back, type ==> final ]
  ],
  []
).
