% Shape (c): the limit comes in the pipe (the recursive situation's
% in_arg), the callee counts the calls in a global and ends in
% `ticked(C)`; the callee hands the pipe back (`out_arg ==> P`, P its
% in_arg); the caller compares with `=:=`.
diag_mod(driver,
  [ [ id ==> again,
      type ==> recursive,
      in_arg ==> Limit,
      embedded_dm ==> tick,
      arcs ==> [ ticked(C) : empty => (C =:= Limit -> halt ; otherwise -> again) ]
    ],
    [ id ==> halt, type ==> final ]
  ],
  []
).

diag_mod(tick,
  [ [ id ==> count,
      type ==> neutral,
      in_arg ==> P,
      out_arg ==> P,
      arcs ==> [ empty : [inc(ticks, C)] => ticked(C) ]
    ],
    [ id ==> ticked(C), type ==> final ]
  ],
  []
).
