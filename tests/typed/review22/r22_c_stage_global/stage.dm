% stage: lit while the fuel (the pipe) is positive, a dud otherwise; the
% pipe handed back unchanged.
diag_mod(stage,
  [ [ id ==> ignite,
      type ==> neutral,
      in_arg ==> Fuel,
      out_arg ==> Fuel,
      arcs ==> [ empty : empty => (Fuel > 0 -> lit ; otherwise -> dud) ]
    ],
    [ id ==> lit, type ==> final ],
    [ id ==> dud, type ==> final ]
  ],
  []
).
