diag_mod(main,
[
  [id ==> is type ==> neutral, arcs ==> [empty : [] => fs]],
  [id ==> fs, type ==> final]
],
[]).
