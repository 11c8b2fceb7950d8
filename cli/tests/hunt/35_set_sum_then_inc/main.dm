% Adding one by `set(count, C + 1)` (set stores its argument as written:
% the term `0+1`), then counting on with `inc`.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [get(count, C), set(count, C + 1), say(get(count, _))] => again ] ],
    [ id ==> again, type ==> neutral,
      arcs ==> [ empty : [inc(count, N), say(N)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ count ==> 0 ]).
