% in_arg patterns matched against the pipe (`npipe14`): a pair set once and
% read back by a callee and by a neutral situation (`c_pipe_pair`'s shape),
% a nested pattern `f(A, [B|C])`, a pattern sharing a variable with the
% situation's id (`same(A)`) and one sharing a DM parameter (`K-Max`).
% `main(Max, Tag)`: Max calls of `count` (at least one), then the nested
% patterns with Tag inside; a Max that is no number is the comparison's
% error.
diag_mod(main(Max, Tag),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> count,
      arcs ==> [ counted : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> N-Lim,
      arcs ==> [ empty : empty => (N < Lim -> ask ; otherwise -> nest) ] ],
    [ id ==> nest, type ==> neutral, in_arg ==> N-_, out_arg ==> f(N, [Tag, N]),
      arcs ==> [ empty : empty => open ] ],
    [ id ==> open, type ==> neutral, in_arg ==> f(A, [B|C]), out_arg ==> g(B, C, A),
      arcs ==> [ empty : empty => (B == stop -> over ; otherwise -> same(A)) ] ],
    [ id ==> same(A), type ==> neutral, in_arg ==> g(_, [A], A), out_arg ==> A-Max,
      arcs ==> [ empty : empty => param ] ],
    [ id ==> param, type ==> neutral, in_arg ==> K-Max, out_arg ==> done(K),
      arcs ==> [ empty : empty => over ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(count,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => counted ] ],
    [ id ==> counted, type ==> final ]
  ],
  []
).

% `shape(P)`: the pipe set to P, matched by the recursive situation's
% `A-B` and the callee's (a pipe of another shape: skipped with a
% warning, D-8), then by the caller's.
diag_mod(shape(P),
  [ [ id ==> s0, type ==> neutral, out_arg ==> P, arcs ==> [ empty : empty => s1 ] ],
    [ id ==> s1, type ==> recursive, in_arg ==> A-B, out_arg ==> A-B, embedded_dm ==> split,
      arcs ==> [ lt : empty => s2, ge : empty => s2 ] ],
    [ id ==> s2, type ==> neutral, in_arg ==> A-B, out_arg ==> B-A,
      arcs ==> [ empty : empty => (A == B -> s3 ; otherwise -> s3) ] ],
    [ id ==> s3, type ==> final ]
  ],
  []
).

diag_mod(split,
  [ [ id ==> sp, type ==> neutral, in_arg ==> A-B,
      arcs ==> [ empty : empty => (A < B -> lt ; otherwise -> ge) ] ],
    [ id ==> lt, type ==> final ],
    [ id ==> ge, type ==> final ]
  ],
  []
).

% `entry`: the command line's pipe matched by a nested pattern.
diag_mod(entry,
  [ [ id ==> e0, type ==> neutral, in_arg ==> f(A, [B|C]), out_arg ==> C-A,
      arcs ==> [ empty : empty => (B == yes -> e1 ; otherwise -> e2) ] ],
    [ id ==> e1, type ==> final ],
    [ id ==> e2, type ==> final ]
  ],
  []
).

% `odd`: an int pipe matched by `N-L`, which can never match (its
% variables typed `never`): skipped with a warning (an error denied).
diag_mod(odd,
  [ [ id ==> o0, type ==> neutral, out_arg ==> 5, arcs ==> [ empty : empty => o1 ] ],
    [ id ==> o1, type ==> neutral, in_arg ==> N-L, out_arg ==> L,
      arcs ==> [ empty : empty => (N == 1 -> o2 ; otherwise -> o2) ] ],
    [ id ==> o2, type ==> final ]
  ],
  []
).

% `looped`: a situation entered three times with a pipe its in_arg never
% matches (`none`): skipped each time, warned about once.
diag_mod(looped,
  [ [ id ==> l0, type ==> neutral, in_arg ==> go(_),
      arcs ==> [ empty : [inc(n, N)] => (N >= 3 -> l1 ; otherwise -> l0) ] ],
    [ id ==> l1, type ==> final ]
  ],
  [ n ==> 0 ]
).
