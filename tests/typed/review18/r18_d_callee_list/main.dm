% review18 (issue 37, shape (d)): a callee returns a list the caller walks.
% `plan(Stops)` reverses the stops into a route (an accumulator in the id)
% and ends in `route(R)`; the caller walks the route in its own situations
% looking for `Dock`. `courier(Rounds, Stops, Dock)`.
diag_mod(courier(Rounds, Stops, Dock),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> plan(Stops),
      arcs ==> [ route(R) : empty => go(R) ] ],
    [ id ==> go([]), type ==> neutral,
      arcs ==> [ empty : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> go([S|Ss]), type ==> neutral,
      arcs ==> [ empty : empty => (S == Dock -> docked ; otherwise -> go(Ss)) ] ],
    [ id ==> docked, type ==> neutral,
      arcs ==> [ empty : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(plan(Stops),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => rev(Stops, []) ] ],
    [ id ==> rev([], Acc), type ==> neutral,
      arcs ==> [ empty : empty => route(Acc) ] ],
    [ id ==> rev([S|Ss], Acc), type ==> neutral,
      arcs ==> [ empty : empty => rev(Ss, [S|Acc]) ] ],
    [ id ==> route(_), type ==> final ]
  ],
  []
).
