% Two globals read into the same variable in one condition:
% `get(left, D) == get(right, D)`. Evaluated left to right, the first `get`
% binds `D` and the second unifies `D` with its own value, so the
% comparison is `true` where both hold the same value and an error
% otherwise (D-34, D-38); never a plain `false`. `top` calls `relay` so
% that native code runs it as well as the machine.
diag_mod(top(X),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> relay(X),
      arcs ==> [ same : empty => fs, other : empty => fs ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(relay(X),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> setter(X),
      arcs ==> [ done : empty => (get(left, D) == get(right, D) -> same ; otherwise -> other) ]
    ],
    [ id ==> same, type ==> final ],
    [ id ==> other, type ==> final ]
  ],
  []
).

diag_mod(setter(X),
  [ [ id ==> put, type ==> neutral, arcs ==> [ empty : set(left, X) => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).
