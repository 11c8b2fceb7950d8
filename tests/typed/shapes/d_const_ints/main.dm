% Shape (d) over integers: a constant list of ints written in the call,
% the target compared with `=:=`; the walk `at([N|Ns])`; finals `hit(N)` and
% `miss`; rounds in the caller's id.
diag_mod(drill(Rounds, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => go(0) ] ],
    [ id ==> go(I),
      type ==> recursive,
      embedded_dm ==> probe([12, 7, 33, 41, 5, 18, 29, 64], Target),
      arcs ==> [ hit(N) : [J is I + 1] => (J < Rounds -> go(J) ; otherwise -> halt),
                 miss : [J is I + 1] => (J < Rounds -> go(J) ; otherwise -> halt) ]
    ],
    [ id ==> halt, type ==> final ]
  ],
  []
).

diag_mod(probe(Ns, T),
  [ [ id ==> first, type ==> neutral, arcs ==> [ empty : empty => at(Ns) ] ],
    [ id ==> at([]), type ==> neutral, arcs ==> [ empty : empty => miss ] ],
    [ id ==> at([N|Ns2]),
      type ==> neutral,
      arcs ==> [ empty : empty => (N =:= T -> hit(N) ; otherwise -> at(Ns2)) ]
    ],
    [ id ==> hit(N), type ==> final ],
    [ id ==> miss, type ==> final ]
  ],
  []
).
