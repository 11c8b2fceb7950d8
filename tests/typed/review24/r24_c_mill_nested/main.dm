% Helper review24 (issue 37, shape c): two nested embedded DMs, the count a
% float in the recursive situation's id (`mill(K)`, one added by `is` in
% the exit arc's action), the budget the pipe, read by the recursive
% situation's in_arg; `grind` calls `blade` (a call inside the callee),
% which hands the pipe back by out_arg, and `grind` decides by the pipe's
% sign which final its caller sees.
diag_mod(works,
  [ [ id ==> open,
      type ==> neutral,
      arcs ==> [ empty : empty => mill(0.0) ]
    ],
    [ id ==> mill(K),
      type ==> recursive,
      in_arg ==> Budget,
      embedded_dm ==> grind,
      arcs ==> [ kept : [K1 is K + 1.0] => (K1 >= Budget -> idle ; otherwise -> mill(K1)),
                 worn : empty => idle ]
    ],
    [ id ==> idle, type ==> final ]
  ],
  []
).

diag_mod(grind,
  [ [ id ==> turn,
      type ==> recursive,
      in_arg ==> W,
      embedded_dm ==> blade,
      arcs ==> [ sharp : empty => (W > 0 -> kept ; otherwise -> worn) ]
    ],
    [ id ==> kept, type ==> final ],
    [ id ==> worn, type ==> final ]
  ],
  []
).

diag_mod(blade,
  [ [ id ==> hone,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => sharp ]
    ],
    [ id ==> sharp, type ==> final ]
  ],
  []
).
