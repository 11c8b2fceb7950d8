% review17 (issue 37, shape c): the pipe carries a pair, `job(Left, Done)`;
% the worker counts one down and the other up and hands it back; the
% caller reads it in the situation after the call and stops at 0.
% 4 transitions a shift.
diag_mod(shift(N),
  [ [ id ==> open,
      type ==> neutral,
      out_arg ==> job(N, 0),
      arcs ==> [ empty : empty => work ]
    ],
    [ id ==> work,
      type ==> recursive,
      embedded_dm ==> worker,
      arcs ==> [ clocked : empty => fork ]
    ],
    [ id ==> fork,
      type ==> neutral,
      in_arg ==> job(L, _),
      arcs ==> [ empty : empty => (L =< 0 -> close ; otherwise -> work) ]
    ],
    [ id ==> close, type ==> final ]
  ],
  []
).

diag_mod(worker,
  [ [ id ==> punch,
      type ==> neutral,
      in_arg ==> job(L, D),
      out_arg ==> job(L1, D1),
      arcs ==> [ empty : [L1 is L - 1, D1 is D + 1] => clocked ]
    ],
    [ id ==> clocked, type ==> final ]
  ],
  []
).
