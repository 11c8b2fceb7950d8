% A global (`calls`) and a local of the same name in the callee: the
% caller's `inc` in its exit arc is the global's (it has no such local),
% the callee's its own local's (the locals first, D-38); a float global
% counted too (`weight`), and a global set to a bound variable's value
% (`set(last, C)`).
diag_mod(relay(Max),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> mirror,
      arcs ==> [ back(_) : [inc(calls, C), inc(weight, _), set(last, C)] => (C < Max -> ask ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(mirror,
  [ [ id ==> take, type ==> neutral, arcs ==> [ empty : [inc(calls, L)] => back(L) ] ],
    [ id ==> back(_), type ==> final ]
  ],
  [ calls ==> 100 ]
).
