% A user function of one argument applied to two values: `double(_X)`
% with `[2, 3]`.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(apply(double(_X), [2, 3])) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
