% Shape (c) as the issue words it: the limit is the recursive situation's
% in_arg (the pipe, set once from the parameter), the callee hands it back
% with `out_arg ==> X`, X its own in_arg; the count is in the caller's id.
% `relay(Max)` makes Max calls of `mirror` (at least one).
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
