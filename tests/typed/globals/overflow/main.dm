% A global counted by `inc` in an exit arc until it overflows (the
% machine's error, with its message and place) unless the flag it
% reads (`get(done, D) == yes`) stops the loop first.
diag_mod(relay(Max),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> mirror,
      arcs ==> [ back : [inc(calls, C)] => (get(done, D) == yes -> over ; otherwise -> (C < Max -> ask ; otherwise -> over)) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(mirror,
  [ [ id ==> take, type ==> neutral, arcs ==> [ empty : empty => back ] ],
    [ id ==> back, type ==> final ]
  ],
  []
).
