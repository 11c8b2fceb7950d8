% The runtime's `when/3` with a comparison whose operands are expressions
% (`N + 1 > L`, `N * 2 =< L - 1`, `-N >= 0 - L`): each operand's value is
% the compound of its arguments' values (D-36), which the comparison
% evaluates (D-34); its error is the comparison's, blaming it. In an
% action, a next situation, an out_arg and a conjunction's operand. `N`
% and `L` may be ints, floats, atoms, unbound, or large enough to overflow.
diag_mod(wexp(N, L),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : [say(apply(when(_, _, _), [N + 1 > L, over(N), under(L)]))]
                   => apply(when(_, _, _), [N * 2 =< L - 1, low, high]) ] ],
    [ id ==> low, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [-N >= 0 - L, neg, pos]),
      arcs ==> [ empty : empty => fin ] ],
    [ id ==> high, type ==> neutral,
      arcs ==> [ empty : empty => ((N + 1 > L, L - 1 < N * 2) -> fin ; otherwise -> fin2) ] ],
    [ id ==> fin, type ==> final ],
    [ id ==> fin2, type ==> final ]
  ],
  []
).

% A count in the id, compared as an expression with the limit in the
% `when/3` of the next situation: `tick(0)` to `done`.
diag_mod(count(Max),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : empty => tick(0) ] ],
    [ id ==> tick(J), type ==> neutral,
      arcs ==> [ empty : [J1 is J + 1]
                   => apply(when(_, _, _), [J1 * 2 < Max * 2, tick(J1), done]) ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).
