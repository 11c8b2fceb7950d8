% `plain_compounds` (helper `nfn19`, issue 37) with a clause that names
% `assertz/1` in its user_functions.pl: no function is plain, every call
% a query of the engine, and the runs are the same as with the plain forms
% (tests/tests/suite/typed/plain_compounds.rs). Its DMs are those of
% `plain_compounds`, line for line (the errors name the lines).
%
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
