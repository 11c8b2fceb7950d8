% N DM calls passing the pipe: `main(Max)` with in_arg 0 calls add_one
% until the pipe reaches Max (4 transitions per call).
diag_mod(main(Max),
  [ [ id ==> call,
      type ==> recursive,
      embedded_dm ==> add_one,
      arcs ==> [ done : empty => check ]
    ],
    [ id ==> check,
      type ==> neutral,
      in_arg ==> X,
      arcs ==> [ empty : empty => (X >= Max -> fs ; otherwise -> call) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(add_one,
  [ [ id ==> is,
      type ==> neutral,
      in_arg ==> A,
      out_arg ==> B,
      prog ==> [B is A + 1],
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).
