% Helper nwinch25 (issue 37): type tests in conditions on values native
% code holds: a parameter (any ground value, or a term), negated, in
% combination with a comparison, in an action and in a next situation.
diag_mod(kinds(X),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : [ (number(X) -> number ; otherwise -> no_number),
                           (integer(X) -> integer ; otherwise -> no_integer),
                           (float(X) -> float ; otherwise -> no_float),
                           (atom(X) -> atom ; otherwise -> no_atom),
                           (atomic(X) -> atomic ; otherwise -> no_atomic),
                           (compound(X) -> compound ; otherwise -> no_compound),
                           (is_list(X) -> list ; otherwise -> no_list),
                           (var(X) -> var ; otherwise -> no_var),
                           (nonvar(X) -> nonvar ; otherwise -> no_nonvar),
                           (ground(X) -> ground ; otherwise -> no_ground),
                           (\+ number(X) -> not_number ; otherwise -> a_number),
                           (\+ \+ atom(X) -> atom2 ; otherwise -> no_atom2) ]
                 => (compound(X) -> parts ; otherwise -> (atomic(X) -> plain ; otherwise -> other)) ]
    ],
    [ id ==> parts, type ==> neutral, arcs ==> [ empty : say(parts) => fin ] ],
    [ id ==> plain, type ==> neutral, arcs ==> [ empty : say(plain) => fin ] ],
    [ id ==> other, type ==> neutral, arcs ==> [ empty : say(other) => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

% In combination: a comparison after a number test (the evaluator
% evaluates both before the call: an atom raises), a disjunction of type
% tests, a conjunction of negated ones.
diag_mod(both(X),
  [ [ id ==> a,
      type ==> neutral,
      arcs ==> [ empty : [ (integer(X) ; float(X) -> num ; otherwise -> other),
                           (\+ atom(X), \+ is_list(X) -> neither ; otherwise -> some) ]
                 => (number(X), X > 3 -> big ; otherwise -> small) ]
    ],
    [ id ==> big, type ==> final ],
    [ id ==> small, type ==> final ]
  ],
  []
).

% A type test in a conjunction in a situation native code does not run
% (`@<` is a condition it leaves to the machine): the term code's
% junction calls the type test as a goal.
diag_mod(mixed(X),
  [ [ id ==> a,
      type ==> neutral,
      arcs ==> [ empty : [ (atom(X), X \== z -> yes ; otherwise -> no),
                           (\+ integer(X) ; X > 2 -> over ; otherwise -> under) ]
                 => (X @< m -> low ; otherwise -> high) ]
    ],
    [ id ==> low, type ==> final ],
    [ id ==> high, type ==> final ]
  ],
  []
).
