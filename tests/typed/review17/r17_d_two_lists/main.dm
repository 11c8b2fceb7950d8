% review17 (issue 37, shape d): `audit(Rounds, Shelves, Item)`; the sweep
% carries two lists in its id, the shelves to go and the shelves seen
% (`pass(Todo, Seen)`), and ends in `spotted(S, Seen)` or
% `absent(Seen)`. The caller matches `spotted(S, _)`, and `absent([])`
% only: a sweep of a non-empty list that finds nothing ends in a final
% situation no exit arc matches.
diag_mod(audit(Rounds, Shelves, Item),
  [ [ id ==> check,
      type ==> recursive,
      embedded_dm ==> sweep(Item, Shelves),
      arcs ==> [ spotted(_, _) : [inc(n, N)] => (N >= Rounds -> report ; otherwise -> check),
                 absent([]) : empty => report ]
    ],
    [ id ==> report, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(sweep(Item, Shelves),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => pass(Shelves, []) ]
    ],
    [ id ==> pass([], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => absent(Seen) ]
    ],
    [ id ==> pass([S|Ss], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == Item -> spotted(S, Seen) ; otherwise -> pass(Ss, [S|Seen])) ]
    ],
    [ id ==> spotted(_, _), type ==> final ],
    [ id ==> absent(_), type ==> final ]
  ],
  []
).
