% Shape (c): N calls of an embedded DM, the limit carried in the pipe as a
% pair `N-Limit` into the **recursive** situation's own in_arg pattern
% (`in_arg ==> N-Lim`); the callee counts (`M is N + 1`) and hands both
% values back (`out_arg ==> M-L`); the caller's exit arc compares the
% count it read before the call with the limit. `relay(Max)` makes Max
% calls of `count` (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 1-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> N-Lim, embedded_dm ==> count,
      arcs ==> [ counted : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(count,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => counted ] ],
    [ id ==> counted, type ==> final ]
  ],
  []
).
