diag_mod(main,
[
  [id ==> is, type ==> neutral, arcs ==> [empty : [say(hello) => fs]],
  [id ==> fs, type ==> final]
],
[]).
