% Situations without id, type or arcs, and a DM without a final situation.
diag_mod(broken,
[
  [type ==> neutral, arcs ==> [empty : [] => s2]],
  [id ==> s2, arcs ==> [empty : [] => s3]],
  [id ==> s3, type ==> speech]
],
[]).
