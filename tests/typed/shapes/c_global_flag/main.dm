% Shape (c): a global flag (`done`, in `global_vars.pl`) set by the callee
% when its own global count (`jobs`) reaches the limit, the caller's
% parameter passed to it; the caller's exit arc tests the flag in its
% condition (`get(done, D) == yes`).
diag_mod(boss(Max),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> worker(Max),
      arcs ==> [ back : empty => (get(done, D) == yes -> over ; otherwise -> ask) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(worker(Max),
  [ [ id ==> work,
      type ==> neutral,
      arcs ==> [ empty : [inc(jobs, J)] => (J >= Max -> finish ; otherwise -> back) ]
    ],
    [ id ==> finish, type ==> neutral, arcs ==> [ empty : set(done, yes) => back ] ],
    [ id ==> back, type ==> final ]
  ],
  []
).
