% Shape (c): N calls of an embedded DM, the count in the caller's id and
% the limit a parameter, the exit arc's condition comparing two
% arithmetic expressions (`J * 2 < Max * 2`: the operands are not
% registers but expressions of them). `relay(Max)` makes Max calls of
% `tick` (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I), type ==> recursive, embedded_dm ==> tick,
      arcs ==> [ ticked : [J is I + 1] => (J * 2 < Max * 2 -> ask(J) ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(tick,
  [ [ id ==> step, type ==> neutral, arcs ==> [ empty : empty => ticked ] ],
    [ id ==> ticked, type ==> final ]
  ],
  []
).
