% Shape (c): the count a global (`calls`, in `global_vars.pl`), counted by
% `inc` in the exit arc and compared with the limit, the DM's parameter;
% the callee hands the pipe back (`out_arg ==> X`).
diag_mod(relay(Max),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> mirror,
      arcs ==> [ back : [inc(calls, C)] => (C < Max -> ask ; otherwise -> over) ]
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
