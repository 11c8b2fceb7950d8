% nuni19 (issue 37): actions performed by native code after an evaluation
% in the same arc entered the situation (`Cx::nat_perform` with the arc's
% index, the runtime's `machine::effect`), in callees below a native
% caller: `visit` without locals (no hand-over before the action), `tally`
% with a local (its own hand-over first). The test's effector answers by
% place (tests/tests/suite/typed.rs, `Errands`): an evaluated action list
% whose first effector fails (`cellar`), a list whose second item fails
% after an evaluated `say` (`pantry`), a `say` of a term that is not
% ground (`garden`), an action of a DM with locals that fails (`vault`).
diag_mod(errand(Places),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => go(Places) ] ],
    [ id ==> go([]), type ==> neutral,
      arcs ==> [ empty : say(apply(twice(_), [done])) => done ] ],
    [ id ==> go([P|Ps]),
      type ==> recursive,
      embedded_dm ==> visit(P, _),
      arcs ==> [ success : empty => count(P, Ps),
                 error(E) : say(['Could not visit', P, E]) => count(P, Ps) ]
    ],
    [ id ==> count(P, Ps),
      type ==> recursive,
      embedded_dm ==> tally(P, _),
      arcs ==> [ done : empty => go(Ps) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(visit(Place, _Status),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : apply(twice(_), [navigate(Place, Result)]) => moved(Result) ]
    ],
    [ id ==> moved(ok),
      type ==> neutral,
      arcs ==> [ empty : [say(apply(twice(_), [Place])), grasp(Place, left, R)] => grabbed(R) ]
    ],
    [ id ==> moved(blocked(A, B)),
      type ==> neutral,
      arcs ==> [ empty : say(apply(twice(_), [A-B])) => error(blocked) ]
    ],
    [ id ==> moved(R),
      type ==> neutral,
      arcs ==> [ empty : say(apply(twice(_), [R])) => error(lost) ]
    ],
    [ id ==> grabbed(ok), type ==> neutral,
      arcs ==> [ empty : apply(twice(_), [stop]) => success ] ],
    [ id ==> grabbed(_), type ==> neutral, arcs ==> [ empty : empty => error(dropped) ] ],
    [ id ==> success, type ==> final, diag_mod ==> visit(Place, ok) ],
    [ id ==> error(E), type ==> final, diag_mod ==> visit(Place, E) ]
  ],
  []
).

diag_mod(tally(Place, _Status),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(n, N), check(Place)] => told(N) ]
    ],
    [ id ==> told(N),
      type ==> neutral,
      arcs ==> [ empty : say(apply(twice(_), [N])) => done ]
    ],
    [ id ==> done, type ==> final, diag_mod ==> tally(Place, ok) ]
  ],
  [n ==> 0]
).
