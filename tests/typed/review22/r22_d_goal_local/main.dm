% Helper review22 (issue 37, shape d): the walker in its own file; the
% rounds left carried in the pipe (a neutral `tick` takes one off by `is`
% and hands it on by out_arg).
diag_mod(errands(Rounds, Spots, Goal),
  [ [ id ==> start,
      type ==> neutral,
      out_arg ==> Rounds,
      arcs ==> [ empty : empty => call ]
    ],
    [ id ==> call,
      type ==> recursive,
      embedded_dm ==> visit(Spots, Goal),
      arcs ==> [ found(_) : empty => tick,
                 not_found : empty => tick ]
    ],
    [ id ==> tick,
      type ==> neutral,
      in_arg ==> Left,
      out_arg ==> L1,
      arcs ==> [ empty : [L1 is Left - 1] => (L1 > 0 -> call ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).
