% Helper ngauge25 (issue 37, shape c): a float `is` in a `prog`. Each
% round the caller calls `drain`, whose situation takes the charge
% by in_arg, computes the next one in its prog (`L1 is L * 2.0 * 0.25 +
% 1.25`)
% and hands it on by out_arg; the charge decides which final is reached.
diag_mod(battery(Rounds, Charge),
  [ [ id ==> start, type ==> neutral, out_arg ==> Charge, arcs ==> [ empty : empty => cycle(0) ] ],
    [ id ==> cycle(I),
      type ==> recursive,
      embedded_dm ==> drain,
      arcs ==> [ ok : [J is I + 1] => (J < Rounds -> cycle(J) ; otherwise -> stop),
                 flat : [J is I + 1] => (J < Rounds -> cycle(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(drain,
  [ [ id ==> use,
      type ==> neutral,
      in_arg ==> L,
      out_arg ==> L1,
      prog ==> [L1 is L * 2.0 * 0.25 + 1.25],
      arcs ==> [ empty : empty => (L1 > 100.0 -> flat ; otherwise -> ok) ]
    ],
    [ id ==> ok, type ==> final ],
    [ id ==> flat, type ==> final ]
  ],
  []
).

% The same with a sum of the pipe's values first (`(L + L) * 0.25`: an
% int or a float by the value, known at run time only).
diag_mod(spend(Rounds, Charge),
  [ [ id ==> start, type ==> neutral, out_arg ==> Charge, arcs ==> [ empty : empty => cycle(0) ] ],
    [ id ==> cycle(I),
      type ==> recursive,
      embedded_dm ==> drain_sum,
      arcs ==> [ ok : [J is I + 1] => (J < Rounds -> cycle(J) ; otherwise -> stop),
                 flat : [J is I + 1] => (J < Rounds -> cycle(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(drain_sum,
  [ [ id ==> use,
      type ==> neutral,
      in_arg ==> L,
      out_arg ==> L1,
      prog ==> [L1 is (L + L) * 0.25 + 1],
      arcs ==> [ empty : empty => (L1 > 100.0 -> flat ; otherwise -> ok) ]
    ],
    [ id ==> ok, type ==> final ],
    [ id ==> flat, type ==> final ]
  ],
  []
).
