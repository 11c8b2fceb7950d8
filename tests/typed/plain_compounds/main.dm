% Plain Prolog user functions that take and return compounds and lists
% (helper `nfn19`, issue 37). `main(Cases)`: each case `c(Op, X)` says
% `shape(Op, X)`. `trip(Places, Target)`: the next situation of a walk is
% the value of `step/3` (`found(P)`, `walk(Ps)`, or a bad one). The
% compiled task and the interpreter's plans must give what the engine
% alone gives (tests/tests/suite/typed.rs, `plain_compounds_agree`).
diag_mod(main(Cases),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => go(Cases) ] ],
    [ id ==> go([]), type ==> final ],
    [ id ==> go([c(Op, X)|Cs]), type ==> neutral,
      arcs ==> [ empty : [say(apply(shape(_, _), [Op, X]))] => go(Cs) ] ]
  ],
  []
).

diag_mod(trip(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(Places) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> walk([P|Ps]), type ==> neutral,
      arcs ==> [ empty : [say(P)] => apply(step(_, _, _), [P, Ps, Target]) ] ],
    [ id ==> found(_), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
