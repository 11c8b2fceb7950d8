% A global declared with `=>` for `==>` in global_vars.pl, then read.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(['Battery at', get(battery, _)]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
