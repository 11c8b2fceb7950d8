% `inc` of a local whose value is not a number, in a situation's prog (set at run time to a value not known to check: no E0242).
diag_mod(main,
  [ [ id ==> is, type ==> neutral, prog ==> [N = bob, set(name, N)], arcs ==> [ empty : [] => s2 ] ],
    [ id ==> s2, type ==> neutral, prog ==> [inc(count, _), inc(name, _)],
      arcs ==> [ empty : [] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [count ==> 0, name ==> bob]).
