% Shape (c): the count is the callee's parameter and its first situation
% names it (`first(N)` in DM `bump(N)`: the id's variable is the
% parameter's, D-7); the callee hands back `bumped(M)`, the limit the
% recursive situation's in_arg.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> Max, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> bump(I),
      arcs ==> [ bumped(J) : empty => (J < Lim -> ask(J) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(bump(N),
  [ [ id ==> first(N), type ==> neutral, arcs ==> [ empty : [M is N + 1] => bumped(M) ] ],
    [ id ==> bumped(M), type ==> final ]
  ],
  []
).
