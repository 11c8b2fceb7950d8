% review17 (issue 37, shape c): the callee counts. `patrol(Laps)` starts
% the pipe at 0; each lap calls `step`, whose in_arg K and out_arg K1
% (K1 is K + 1 in the arc's action) hand the count back, and whose final
% situation carries it too: the caller's exit arc compares it with the
% parameter. 3 transitions a lap.
diag_mod(patrol(Laps),
  [ [ id ==> start,
      type ==> neutral,
      out_arg ==> 0,
      arcs ==> [ empty : empty => lap ]
    ],
    [ id ==> lap,
      type ==> recursive,
      embedded_dm ==> step,
      arcs ==> [ moved(M) : empty => (M >= Laps -> park ; otherwise -> lap) ]
    ],
    [ id ==> park, type ==> final ]
  ],
  []
).

diag_mod(step,
  [ [ id ==> tick,
      type ==> neutral,
      in_arg ==> K,
      out_arg ==> K1,
      arcs ==> [ empty : [K1 is K + 1] => moved(K1) ]
    ],
    [ id ==> moved(_), type ==> final ]
  ],
  []
).
