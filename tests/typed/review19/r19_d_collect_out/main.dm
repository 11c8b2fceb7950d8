% Helper review19 (issue 37, shape d): a walk that accumulates a result
% list in its id and passes it on by `out_arg`. `harvest(Rounds, Readings,
% Limit)`: each round calls `sieve(Readings, Limit)`, which keeps the
% readings above `Limit` and hands them back down the pipe; the final
% situation of `harvest` takes the last result as its in_arg.
diag_mod(harvest(Rounds, Readings, Limit),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> sieve(Readings, Limit),
      arcs ==> [ kept : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final, in_arg ==> _Kept ]
  ],
  [ done ==> 0 ]
).

diag_mod(sieve(Readings, Limit),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => pass(Readings, []) ]
    ],
    [ id ==> pass([], Acc),
      type ==> neutral,
      out_arg ==> Acc,
      arcs ==> [ empty : empty => kept ]
    ],
    [ id ==> pass([R|Rs], Acc),
      type ==> neutral,
      arcs ==> [ empty : empty => (R > Limit -> pass(Rs, [R|Acc]) ; otherwise -> pass(Rs, Acc)) ]
    ],
    [ id ==> kept, type ==> final ]
  ],
  []
).
