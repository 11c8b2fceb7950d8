% Shape (d): a walk with a guard: places on a skip list are passed over
% (`member`), the others compared with the target (`\==` first); the
% caller's exit arc `found(P)` uses P in its action list.
diag_mod(visit(Times, Places, Skip, Target),
  [ [ id ==> again,
      type ==> recursive,
      embedded_dm ==> walk(Places, Skip, Target),
      arcs ==> [ found(P) : [inc(n, N), P] => (N >= Times -> fin ; otherwise -> again),
                 none : [inc(n, N)] => (N >= Times -> fin ; otherwise -> again) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(walk(Places, Skip, Target),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => w(Places) ] ],
    [ id ==> w([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => (member(P, Skip) -> w(Ps) ;
                                        otherwise -> (P \== Target -> w(Ps) ; otherwise -> found(P))) ] ],
    [ id ==> w([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
