% The runtime's `when/3` (`apply(when(_, _, _), [C, T, E])`: `T` if `C`,
% its value, holds as a goal, else `E`) in an out_arg, a next situation and
% an action; nested (in a branch: the evaluator's); a condition that errors
% (an arithmetic comparison of atoms or of an unbound variable) and one that
% is not a comparison (`Z`: `true` holds, `false` does not, a value that is
% no goal is an error).
diag_mod(main(X, Y, Z),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X == Y, same, other]),
      arcs ==> [ empty : [say(apply(when(_, _, _), [X \== Y, differ, agree]))]
                   => apply(when(_, _, _), [X == Y, eq, ne]) ] ],
    [ id ==> eq, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : [say(P)]
                   => apply(when(_, _, _), [X == a, apply(when(_, _, _), [Y == a, both, one]), neither]) ] ],
    [ id ==> ne, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : [say(P)] => apply(when(_, _, _), [X > Y, big, small]) ] ],
    [ id ==> big, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [Z, yes, no]),
      arcs ==> [ empty : empty => fin ] ],
    [ id ==> small, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [f(X) == f(Z), yes, no]),
      arcs ==> [ empty : [say(apply(when(_, _, _), [Z == Y, [Z], g(Z)]))] => fin ] ],
    [ id ==> both, type ==> final ],
    [ id ==> one, type ==> final ],
    [ id ==> neither, type ==> final ],
    [ id ==> fin, type ==> final ]
  ],
  []
).
