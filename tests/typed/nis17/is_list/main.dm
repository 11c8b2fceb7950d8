% nis17 (issue 37): `V is E` in an action list on values typed `ground`
% (a parameter and the pipe), with other actions between: native checked
% arithmetic where the operands are ints, the machine's `is` (its value or
% its error) for a float, a non-number, an unbound variable or an overflow.
diag_mod(tally(Start, Step),
  [ [ id ==> open,
      type ==> neutral,
      out_arg ==> acc(Start, 0),
      arcs ==> [ empty : empty => add ]
    ],
    [ id ==> add,
      type ==> recursive,
      embedded_dm ==> adder(Step),
      arcs ==> [ added : empty => check ]
    ],
    [ id ==> check,
      type ==> neutral,
      in_arg ==> acc(A, K),
      arcs ==> [ empty : [A, K] => (K >= 3 -> done ; otherwise -> add) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(adder(Step),
  [ [ id ==> sum,
      type ==> neutral,
      in_arg ==> acc(A, K),
      out_arg ==> acc(A1, K1),
      arcs ==> [ empty : [A1 is A + Step, tick, K1 is K + 1, A2 is A1 * 2, A2] => added ]
    ],
    [ id ==> added, type ==> final ]
  ],
  []
).
