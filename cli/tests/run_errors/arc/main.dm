% `pour/1` is defined nowhere (run with --allow-unresolved to reach it).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(hello), apply(pour(D), [D])] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
