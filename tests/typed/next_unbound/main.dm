% A next situation without a value (docs/guide/language.md, "Next"; issue 39's program
% 13): the DM ends there, without a final situation, as the original's
% ends (its unbound next situation is the `empty` that ends a DM); the
% arc's entry is the DM's last, and a caller takes its first exit arc (the
% variable unifies with any expectation). `main` ends the task so;
% `caller(N)` calls `sub` twice, natively: `sub(1)` ends in its final,
% `sub(2)` by the variable, the caller's `done(R)` taken with `R` unbound.
diag_mod(main,
  [ [ id ==> is, type ==> neutral, out_arg ==> started,
      arcs ==> [ empty : say(going) => Next ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(caller(N),
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub(N),
      arcs ==> [ done(R) : say(first(R)) => again, other : say(other) => fs ] ],
    [ id ==> again, type ==> recursive, embedded_dm ==> sub(2),
      arcs ==> [ done(R) : say(second(R)) => fs, other : say(other) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(sub(N),
  [ [ id ==> s1, type ==> neutral, out_arg ==> sub(N),
      arcs ==> [ empty : say(n(N)) => (N > 1 -> Next ; otherwise -> done(N)) ] ],
    [ id ==> done(_), type ==> final ] ],
  []).
