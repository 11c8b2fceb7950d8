% The pipe a pair `N-L` that native code holds as native values while
% native frames hand it on (helper npipe15): set once by `out_arg ==>
% 0-Max`, read and set again by callees two levels down, read by the
% caller's neutral situation; a callee that leaves a pipe of another
% shape (`stop(N, L, end)`, three arguments, held too); a recursive
% situation with an in_arg pattern (term code: the machine reads the pipe
% native code held); a pipe from the command line.

% Calls `outer`, which calls `inner` twice: two levels.
diag_mod(main(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> outer,
      arcs ==> [ done : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> N-Lim,
      arcs ==> [ empty : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(outer,
  [ [ id ==> first, type ==> recursive, embedded_dm ==> inner,
      arcs ==> [ added : empty => second ] ],
    [ id ==> second, type ==> recursive, embedded_dm ==> inner,
      arcs ==> [ added : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(inner,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).

% Native calls of `inner`, then a recursive situation whose in_arg is a
% pattern (term code) reads the pipe they left.
diag_mod(mixed(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> inner,
      arcs ==> [ added : empty => again ] ],
    [ id ==> again, type ==> recursive, in_arg ==> N-L, embedded_dm ==> inner,
      arcs ==> [ added : empty => (N < L -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

% The callee leaves `stop(N, L, end)` at the last call: the caller's
% `N-Lim` does not match it (skipped by the machine with a warning, D-8).
diag_mod(shaped(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> maybe,
      arcs ==> [ added : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> N-Lim,
      arcs ==> [ empty : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(maybe,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L,
      arcs ==> [ empty : empty => (N < 2 -> more ; otherwise -> last) ] ],
    [ id ==> more, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => added ] ],
    [ id ==> last, type ==> neutral, in_arg ==> N-L, out_arg ==> stop(N, L, end),
      arcs ==> [ empty : empty => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).

% The pipe from the command line read by the callee.
diag_mod(entry,
  [ [ id ==> ask, type ==> recursive, embedded_dm ==> inner,
      arcs ==> [ added : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> N-Lim,
      arcs ==> [ empty : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).
