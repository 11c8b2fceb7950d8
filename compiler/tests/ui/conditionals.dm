% Terms written like conditionals: only `(C -> A ; otherwise -> B)` is one
% (W0233 for the others; nested chains are fine).
diag_mod(main(N),
[
  [id ==> is, type ==> neutral,
   arcs ==> [empty : [say((N > 1 -> many ; N == 1 -> one ; otherwise -> none))] => pick]],
  [id ==> pick, type ==> neutral,
   arcs ==> [empty : [say((N > 1 -> many ; few))]
                     => (N > 1 -> fs ; otherwise -> (N == 1 -> fs ; otherwise -> fs))]],
  [id ==> fs, type ==> final]
],
[]).
