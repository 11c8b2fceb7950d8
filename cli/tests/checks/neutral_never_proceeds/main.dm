% A new user's neutral situations (issue 39, session 16): two arcs, and
% one arc whose expectation is never `empty`, stop the run when reached
% (E0236); a variable expectation is taken as `empty` (W0210 only).
diag_mod(main,
  [ [id ==> is, type ==> neutral,
      arcs ==> [empty : say(hello) => two, empty : say(again) => is]],
    [id ==> two, type ==> neutral,
      arcs ==> [go : say(go) => (get(n, N), N > 1 -> three ; otherwise -> fs)]],
    [id ==> three, type ==> neutral,
      arcs ==> [_ : say(any) => fs]],
    [id ==> fs, type ==> final] ],
  [n ==> 0]).
