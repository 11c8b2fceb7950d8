% Typed situations: an int counter compared with a parameter, a float
% local, a local of a finite atom set, constant expectations read from the
% script, and a DM parameter that may not be an int (then the untyped
% path runs).
diag_mod(main(Max),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N), set(mode, counting), inc(f, _)] =>
                   (N >= Max -> listen ; otherwise -> is) ]
    ],
    [ id ==> listen,
      type ==> speech,
      arcs ==> [ tick : [inc(n, _), beep] => listen,
                 half : [set(mode, idle), get(f, F)] =>
                   (F > 2.5 -> done ; otherwise -> listen),
                 mode : [get(mode, M)] => (M == idle -> listen ; otherwise -> done),
                 other : [get(mode, M)] => (M \== counting -> listen ; otherwise -> done),
                 stop : empty => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ n ==> 0, f ==> 0.5, mode ==> idle ]
).

% Overflow: the same error message on both back ends.
diag_mod(big,
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N)] => (N > 0 -> is ; otherwise -> fs) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 9223372036854775805 ]
).
