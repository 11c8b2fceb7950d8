% Shape (d), nested: a walk over a list of atoms that calls a DM per
% element (`check(P)`), which answers `yes`/`no` by comparing with a
% parameter; the walk ends on the first `yes`.
diag_mod(inspect(Times, Items, Bad),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> scan(Items, Bad),
      arcs ==> [ bad(I) : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round),
                 clean : [inc(n, N)] => (N >= Times -> fin ; otherwise -> round) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(scan(Items, Bad),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => each(Items) ] ],
    [ id ==> each([]), type ==> neutral, arcs ==> [ empty : empty => clean ] ],
    [ id ==> each([I|Is]),
      type ==> recursive,
      embedded_dm ==> check(I, Bad),
      arcs ==> [ yes : empty => bad(I), no : empty => each(Is) ] ],
    [ id ==> bad(I), type ==> final ],
    [ id ==> clean, type ==> final ]
  ],
  []
).

diag_mod(check(I, Bad),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => (I == Bad -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).
