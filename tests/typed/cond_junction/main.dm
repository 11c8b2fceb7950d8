% Conjunctions and disjunctions in a conditional's condition (`Cond::And`,
% `Cond::Or`): the evaluator evaluates the condition's arguments before it
% calls it (D-35), so every operand is computed, left to right, whatever
% the left one gave: an operand that errs does so even where the other
% decides (`conj(0, a)`: `0 > 1` false, `a < 2` the error; `disj(2, a)`:
% `2 > 1` true, `a < 2` the error), the left one's error first
% (`conj(a, b)`). `X` and `Y` are numbers, atoms, unbound or floats.
diag_mod(conj(X, Y),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty => ((X > 1, Y < 2) -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

diag_mod(disj(X, Y),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty => ((X > 1 ; Y =< 2) -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

% `==`, `\==`, `member/2`, `not_member/2` and a nested disjunction as
% operands; `=:=` as an operand keeps the whole condition the evaluator's
% (its goal is called only where the disjunction reaches it).
diag_mod(mixed(X, L),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty =>
                   ((X == a ; member(X, L)) -> second ; otherwise -> no) ] ],
    [ id ==> second, type ==> neutral,
      arcs ==> [ empty : empty =>
                   ((not_member(X, L), (X \== b ; X >= 0)) -> third ; otherwise -> no) ] ],
    [ id ==> third, type ==> neutral,
      arcs ==> [ empty : empty => ((X == a ; X =:= 2) -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

% The review's shape: a local counted in the exit arc's action, compared in
% a conjunction with a DM parameter, and the pipe compared with another:
% `lim(N, Want)` calls `leaf` `N` times; `Want` an atom, `N` a number or not.
diag_mod(lim(N, Want),
  [ [ id ==> loop, type ==> recursive,
      embedded_dm ==> leaf(Want),
      arcs ==> [ got(W) : [inc(k, K)] => ((W == Want, K < N) -> loop ; otherwise -> done),
                 none : [inc(k, K)] => ((K >= N ; K > 5) -> done ; otherwise -> loop) ] ],
    [ id ==> done, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(leaf(W),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty => ((W == none ; W == nothing) -> none ; otherwise -> got(W)) ] ],
    [ id ==> got(_), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

% A conjunction in an out_arg's conditional (before a constant next
% situation) and in an action's.
diag_mod(outc(X, Y),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> ((X > 1, Y > 1) -> both ; otherwise -> notboth),
      arcs ==> [ empty : [say(((X > 0 ; Y > 0) -> some ; otherwise -> none))] => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).
