% A call of a function defined nowhere, and one with a typo.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [apply(pour(D), [D]), apply(greting(_), [bob])] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
