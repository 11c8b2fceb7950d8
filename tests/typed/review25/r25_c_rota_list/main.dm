% Helper review25 (issue 37, shape c): a counter in the pipe and a list in
% the recursive situation's id together. `rota(Limit, Crew)` hands one
% shift to each of the crew in turn (`spin([W|Ws])`, refilled from the
% parameter when empty); the callee `shift(W)` hands the pipe back and ends
% `rested` for `cy`, `worked` for anyone else; the caller adds one to the
% pipe in its exit arc and stops at the limit.
diag_mod(rota(Limit, Crew),
  [ [ id ==> spin([]),
      type ==> neutral,
      arcs ==> [ empty : empty => spin(Crew) ]
    ],
    [ id ==> spin([W|Ws]),
      type ==> recursive,
      in_arg ==> K,
      out_arg ==> K1,
      embedded_dm ==> shift(W),
      arcs ==> [ worked : [K1 is K + 1] => (K1 >= Limit -> off ; otherwise -> spin(Ws)),
                 rested : [K1 is K + 1] => (K1 >= Limit -> off ; otherwise -> spin(Ws)) ]
    ],
    [ id ==> off, type ==> final ]
  ],
  []
).

diag_mod(shift(W),
  [ [ id ==> clock,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => (W == cy -> rested ; otherwise -> worked) ]
    ],
    [ id ==> worked, type ==> final ],
    [ id ==> rested, type ==> final ]
  ],
  []
).
