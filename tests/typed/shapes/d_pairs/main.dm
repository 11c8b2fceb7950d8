% Shape (d): a list of pairs `p(Name, N)` walked by `look([p(Name, N)|More])`,
% the name compared with the key; `found(Name, N)`; the caller's exit arc
% reads the number, the other field `_`.
diag_mod(lookup(Times, Table, Key),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> find(Table, Key),
      arcs ==> [ found(_, V) : [inc(asked, A)] => (A >= Times -> end ; otherwise -> ask),
                 absent : [inc(asked, A)] => (A >= Times -> end ; otherwise -> ask) ]
    ],
    [ id ==> end, type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(find(Table, Key),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => look(Table) ] ],
    [ id ==> look([p(Name, N)|More]),
      type ==> neutral,
      arcs ==> [ empty : empty => (Name == Key -> found(Name, N) ; otherwise -> look(More)) ]
    ],
    [ id ==> look([]), type ==> neutral, arcs ==> [ empty : empty => absent ] ],
    [ id ==> found(Name, N), type ==> final ],
    [ id ==> absent, type ==> final ]
  ],
  []
).
