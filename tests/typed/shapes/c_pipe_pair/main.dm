% Shape (c): the pipe a pair `N-Limit`, set once by the first situation;
% the callee counts (`M is N + 1`) and hands both values back
% (`out_arg ==> M-L`); the caller reads the pair on a neutral situation
% and compares. `relay(Max)` makes Max calls of `count` (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> count,
      arcs ==> [ counted : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> N-Lim,
      arcs ==> [ empty : empty => (N < Lim -> ask ; otherwise -> over) ] ],
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
