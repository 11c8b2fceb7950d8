% review18 (issue 37, shape (c)): a call three DMs deep, the limit put in the
% pipe once by the first situation's out_arg, read by the recursive
% situation's in_arg at every round, carried down through `relay` to `leaf`,
% which hands it back with `out_arg ==> X` (X its own in_arg); the rounds
% are counted in a global that `relay` increments and hands up in its final
% situation's id. `top(N)`: N calls.
diag_mod(top(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N,
      arcs ==> [ empty : empty => call ] ],
    [ id ==> call, type ==> recursive, in_arg ==> Limit, embedded_dm ==> relay,
      arcs ==> [ back(K) : empty => (K >= Limit -> fs ; otherwise -> call) ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(relay,
  [ [ id ==> down, type ==> recursive, embedded_dm ==> leaf,
      arcs ==> [ up : [inc(trips, K)] => back(K) ] ],
    [ id ==> back(_), type ==> final ]
  ],
  []
).

diag_mod(leaf,
  [ [ id ==> echo, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => up ] ],
    [ id ==> up, type ==> final ]
  ],
  []
).
