% Shape (d): `search(Places, Target, Found)`, the result bound by the
% finals' `diag_mod`; the caller's exit arc is a variable and its next
% situation reads the output.
diag_mod(hunt(Times),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> search([hall, bath, bed, study, cellar, attic, garage, kitchen], kitchen, Found),
      arcs ==> [ Result : [inc(n, N)] => (N >= Times -> fin ; otherwise -> (Found == none -> fin ; otherwise -> go)) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(search(Places, Target, Found),
  [ [ id ==> s0, type ==> neutral, arcs ==> [ empty : empty => step(Places) ] ],
    [ id ==> step([]), type ==> neutral, arcs ==> [ empty : empty => nothing ] ],
    [ id ==> step([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> got(P) ; otherwise -> step(Ps)) ] ],
    [ id ==> got(P), type ==> final, diag_mod ==> search(Places, Target, P) ],
    [ id ==> nothing, type ==> final, diag_mod ==> search(Places, Target, none) ]
  ],
  []
).
