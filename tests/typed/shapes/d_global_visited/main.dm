% Shape (d): the places visited counted in a global (`visited`, in
% `global_vars.pl`) by `inc` in the walk's arc; the caller reads it in
% its exit arcs (`get(visited, V)`) and stops when it reaches its budget.
diag_mod(hunt(Budget, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round ] ],
    [ id ==> round,
      type ==> recursive,
      embedded_dm ==> seek(Places, Target),
      arcs ==> [ found(P) : [get(visited, V)] => (V < Budget -> round ; otherwise -> stop),
                 not_found : [get(visited, V)] => (V < Budget -> round ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(seek(L, Goal),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(L) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : [inc(visited, _)] => (P == Goal -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
