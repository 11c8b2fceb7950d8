% Helper nplain20 (issue 37): plain Prolog user functions called by native
% code on the values it holds (`Cx::nat_plain`), and every call the native
% form leaves to the engine. `hop(Places, Target)`: the next situation is
% `next_of/3`'s value. `check(Places, Target)`: a condition
% `apply(is_at(_, _), [P, Target]) == yes`. `tick(Start)`: an integer walk
% whose next situation `bump/1` computes (an overflow at the end of `i64`).
diag_mod(hop(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(Places) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> walk([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => apply(next_of(_, _, _), [P, Ps, Target]) ] ],
    [ id ==> found(_), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).

diag_mod(check(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> try([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(is_at(_, _), [P, Target]) == yes -> got(P) ; otherwise -> try(Ps)) ] ],
    [ id ==> got(_), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(tick(Start),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => at(Start) ] ],
    [ id ==> at(N), type ==> neutral, arcs ==> [ empty : empty => apply(bump(_), [N]) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).

% `weigh(Crates)`: the first crate `heavy/1` (an if-then-else) accepts.
diag_mod(weigh(Crates),
  [ [ id ==> load, type ==> neutral, arcs ==> [ empty : empty => crate(Crates) ] ],
    [ id ==> crate([]), type ==> neutral, arcs ==> [ empty : empty => light ] ],
    [ id ==> crate([W|Ws]), type ==> neutral,
      arcs ==> [ empty : empty => (apply(heavy(_), [W]) == yes -> heavy(W) ; otherwise -> crate(Ws)) ] ],
    [ id ==> heavy(_), type ==> final ],
    [ id ==> light, type ==> final ]
  ],
  []
).
