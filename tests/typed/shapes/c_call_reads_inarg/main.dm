% Shape (c): the count carried in the pipe into the recursive situation's
% variable in_arg (`in_arg ==> N`), which only the call it makes reads
% (`embedded_dm ==> count(N, Lim)`; no exit arc reads it); the callee
% counts (`M is N + 1`), hands the new count back as its out_arg and ends
% in `more` or `done` by comparing it with the limit, which the caller
% keeps in its id. `relay(Max)` makes Max calls of `count` (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask(Max) ] ],
    [ id ==> ask(Lim), type ==> recursive, in_arg ==> N, embedded_dm ==> count(N, Lim),
      arcs ==> [ more : empty => ask(Lim), done : empty => over ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(count(N, Lim),
  [ [ id ==> step, type ==> neutral, out_arg ==> M,
      arcs ==> [ empty : [M is N + 1] => (M < Lim -> more ; otherwise -> done) ] ],
    [ id ==> more, type ==> final ],
    [ id ==> done, type ==> final ]
  ],
  []
).
