% Shape (c): the counter is the callee's DM parameter (`mirror(I)`), which
% its final hands back in its id (`back(I)`); the limit is the recursive
% situation's in_arg, handed back by `out_arg ==> X`.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> Max, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> mirror(I),
      arcs ==> [ back(K) : [J is K + 1] => (J >= Lim -> over ; otherwise -> ask(J)) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(mirror(N),
  [ [ id ==> take, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => back(N) ] ],
    [ id ==> back(N), type ==> final ]
  ],
  []
).
