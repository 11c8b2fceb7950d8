% review17 (issue 37, shape c, written without reading tests/typed/shapes):
% a charger pulses a cell `Full` times. The limit enters the pipe in the
% first situation, the recursive situation takes it as its in_arg, the
% cell hands the pipe back from its first of two situations, the count is
% a local and the next situation a `when/3`. 4 transitions a pulse.
diag_mod(charger(Full),
  [ [ id ==> plug,
      type ==> neutral,
      out_arg ==> Full,
      arcs ==> [ empty : empty => cycle ]
    ],
    [ id ==> cycle,
      type ==> recursive,
      in_arg ==> Cap,
      embedded_dm ==> cell,
      arcs ==> [ full : [inc(cycles, C)] => apply(when(_, _, _), [C >= Cap, unplug, cycle]) ]
    ],
    [ id ==> unplug, type ==> final ]
  ],
  [ cycles ==> 0 ]
).

diag_mod(cell,
  [ [ id ==> sense,
      type ==> neutral,
      in_arg ==> V,
      out_arg ==> V,
      arcs ==> [ empty : empty => idle ]
    ],
    [ id ==> idle,
      type ==> neutral,
      arcs ==> [ empty : empty => full ]
    ],
    [ id ==> full, type ==> final ]
  ],
  []
).
