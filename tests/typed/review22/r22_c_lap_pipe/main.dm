% Helper review22 (issue 37, shape c): the count and the limit both in the
% pipe, `lap(K, Max)`; the recursive situation's in_arg takes the pipe
% apart, the callee adds one by `is` and hands back `lap(K1, Max)` by
% out_arg, ending in `going` or `finished`.
diag_mod(track,
  [ [ id ==> start,
      type ==> neutral,
      in_arg ==> Laps,
      out_arg ==> lap(0, Laps),
      arcs ==> [ empty : empty => run ]
    ],
    [ id ==> run,
      type ==> recursive,
      in_arg ==> lap(_Done, _Max),
      embedded_dm ==> runner,
      arcs ==> [ going : empty => run,
                 finished : empty => podium ]
    ],
    [ id ==> podium, type ==> final ]
  ],
  []
).

diag_mod(runner,
  [ [ id ==> stride,
      type ==> neutral,
      in_arg ==> lap(K, M),
      out_arg ==> lap(K1, M),
      arcs ==> [ empty : [K1 is K + 1] => (K1 >= M -> finished ; otherwise -> going) ]
    ],
    [ id ==> going, type ==> final ],
    [ id ==> finished, type ==> final ]
  ],
  []
).
