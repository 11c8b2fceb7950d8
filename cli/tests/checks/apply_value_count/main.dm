% Issue 39, session 18 (first-week program 34): `apply` with more or fewer
% values than the function's arguments (W0251): the original calls it with
% every argument unbound, and so does the run; a list not written as one
% (`get(..)`) is not reported.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(apply(double(_X), [2, 3])),
                          say(apply(add(_A, _B), [1])),
                          say(apply(double(_Y), [4])),
                          say(apply(double(_Z), get(values, _)))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ values ==> [5] ]).
