% A DM whose first situation names its parameter (`q(A)` in `ask(A)`),
% called with the argument unbound (`ask(_X)`): the parameter is `term`,
% `q` code on terms, `r` and `done` native.
diag_mod(main,
  [ [ id ==> s, type ==> recursive, embedded_dm ==> ask(_X),
      arcs ==> [ done(K) : empty => fin(K) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(ask(A),
  [ [ id ==> q(A), type ==> neutral, arcs ==> [ empty : [N is 1 + 1] => r(N) ] ],
    [ id ==> r(M), type ==> neutral, arcs ==> [ empty : [K is M + 1] => done(K) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).
