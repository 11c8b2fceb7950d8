% neff18 (issue 37): actions of effectors performed by native code without
% handing its frames over, in a callee below a native caller: an effector
% binding an output variable (`navigate(Place, Result)`, `grasp`), action
% lists of a `say` of native values then an effector, a constant `say`.
% The test's effector answers by place: `ok`, `blocked(A, B)`, a float, a
% term that is not ground (no native value: the arc's rest on terms), an
% error (the action fails), and a grasp that fails (the second effector
% of a list), and `report(done)`, the second of a constant list, fails
% where nothing was navigated to.
diag_mod(errand(Places),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => go(Places) ] ],
    [ id ==> go([]),
      type ==> neutral,
      arcs ==> [ empty : [say('All done.'), report(done)] => done ]
    ],
    [ id ==> go([P|Ps]),
      type ==> recursive,
      embedded_dm ==> visit(P, _),
      arcs ==> [ success : empty => go(Ps),
                 error(E) : say(['Could not visit', P, E]) => go(Ps) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(visit(Place, _Status),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [say(['Going to the', Place]), navigate(Place, Result)] => moved(Result) ]
    ],
    [ id ==> moved(ok),
      type ==> neutral,
      arcs ==> [ empty : [say(arrived), grasp(Place, left, R)] => grabbed(R) ]
    ],
    [ id ==> moved(blocked(A, B)),
      type ==> neutral,
      arcs ==> [ empty : say([blocked, A, B]) => error(blocked) ]
    ],
    [ id ==> moved(_), type ==> neutral, arcs ==> [ empty : empty => error(lost) ] ],
    [ id ==> grabbed(ok), type ==> neutral, arcs ==> [ empty : stop => success ] ],
    [ id ==> grabbed(_), type ==> neutral, arcs ==> [ empty : empty => error(dropped) ] ],
    [ id ==> success, type ==> final, diag_mod ==> visit(Place, ok) ],
    [ id ==> error(E), type ==> final, diag_mod ==> visit(Place, E) ]
  ],
  []
).
