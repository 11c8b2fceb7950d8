% Helper review22 (issue 37, shape d): a walk of integers for the first
% reading at or above a floor, decided by a plain Prolog user function
% (`reaches/2`); the rounds counted in a global.
diag_mod(meter(Rounds, Readings, Floor),
  [ [ id ==> poll,
      type ==> recursive,
      embedded_dm ==> scan(Readings, Floor),
      arcs ==> [ found(_V) : [inc(polls, P)] => (P >= Rounds -> off ; otherwise -> poll),
                 not_found : [inc(polls, P)] => (P >= Rounds -> off ; otherwise -> poll) ]
    ],
    [ id ==> off, type ==> final ]
  ],
  []
).

diag_mod(scan(Readings, Floor),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Readings) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> try([V|Vs]),
      type ==> neutral,
      arcs ==> [ empty : empty => (apply(reaches(_X, _F), [V, Floor]) == yes -> found(V) ; otherwise -> try(Vs)) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
