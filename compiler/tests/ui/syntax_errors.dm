diag_mod(main,
[
  [id ==> is, type ==> neutral, arcs ==> [empty : [say(a : b : c)] => fs]],
  [id ==> fs, type ==> final],
],
[]).
