% Plain Prolog user functions (helper `nufn17`, issue 37): each case
% `c(Op, X, Y)` says `calc(Op, X, Y)` and compares X and Y by `same/2`
% (where they are the same, says `kind_of/1` of the rest, not plain).
% The plain ones run natively where they can; a case whose call the
% engine decides (a type error, an overflow, a failure, no value) gives
% the engine's value or error (tests/tests/suite/typed.rs).
diag_mod(main(Cases),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => go(Cases) ] ],
    [ id ==> go([]), type ==> final ],
    [ id ==> go([c(Op, X, Y)|Cs]),
      type ==> neutral,
      arcs ==> [ empty : [say(apply(calc(_, _, _), [Op, X, Y]))] =>
                   (apply(same(_, _), [X, Y]) == yes -> eq(Cs) ; otherwise -> go(Cs)) ]
    ],
    [ id ==> eq(Cs), type ==> neutral,
      arcs ==> [ empty : [say(apply(kind_of(_), [Cs]))] => go(Cs) ] ]
  ],
  []
).

% `count(N)`: N calls of `next_of/1` through the pipe (a callee's out_arg).
diag_mod(count(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> step, arcs ==> [ done : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> V,
      arcs ==> [ empty : [say(V)] => (V < N -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(step,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(next_of(_), [X]),
      arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).
