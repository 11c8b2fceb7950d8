% Shape (c), another engineer's: the limit a DM parameter, a call with no
% arguments, the counter incremented by the caller and compared with `<`.
% `counter(Max)` makes Max calls of `ping`.
diag_mod(counter(Max),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> ping,
      arcs ==> [ pong : [inc(calls, C)] => (C < Max -> go ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ calls ==> 0 ]
).

diag_mod(ping,
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => pong ] ],
    [ id ==> pong, type ==> final ]
  ],
  []
).
