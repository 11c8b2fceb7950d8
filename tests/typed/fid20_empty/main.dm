% `=> empty` ends a DM, as the original's first rule for a next situation
% (`empty`'s, tried before any situation) ends it: even in a DM with a
% situation called `empty`, which is never entered. The main DM's end
% ends the task; a callee's final situation is unbound, so its caller
% takes its first exit arc (`took(X)`, `X` unbound). docs/guide/language.md,
% "Next"; issue 39.
diag_mod(main,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub(1),
      arcs ==> [ took(X) : say(took(first, X)) => again, done : say(took(done)) => again ] ],
    [ id ==> again, type ==> neutral, out_arg ==> ended,
      arcs ==> [ empty : say(bye) => empty ] ],
    [ id ==> empty, type ==> neutral, arcs ==> [ empty : say(never) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(sub(N),
  [ [ id ==> s1, type ==> neutral, out_arg ==> sub(N),
      arcs ==> [ empty : say(n(N)) => (N > 0 -> empty ; otherwise -> done) ] ],
    [ id ==> done, type ==> final ] ],
  []).
