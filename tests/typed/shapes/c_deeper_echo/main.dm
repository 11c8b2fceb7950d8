% Shape (c): the callee one level deeper: `relay` calls `hop`, which calls
% `mirror`, which hands the limit back with `out_arg ==> X`; `hop` passes
% the pipe through. The limit is the recursive situation's in_arg.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> Max, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> hop,
      arcs ==> [ done : [J is I + 1] => (J < Lim -> ask(J) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(hop,
  [ [ id ==> down, type ==> recursive, embedded_dm ==> mirror,
      arcs ==> [ back : empty => done ] ],
    [ id ==> done, type ==> final ]
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
