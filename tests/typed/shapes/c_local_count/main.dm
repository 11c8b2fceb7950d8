% Shape (c) counting in locals (`nfx16`): N calls of `tick`, whose arc's
% out_arg counts its own local (`inc(n, _)`: the pipe is 1 at each
% return, the local starting at 0 at each call); the caller counts the
% calls in its own local in the exit arc's next situation
% (`next(inc(calls, _))`) and compares the count with its limit.
diag_mod(relay(Max),
  [ [ id ==> ask, type ==> recursive, embedded_dm ==> tick,
      arcs ==> [ done : empty => next(inc(calls, _)) ] ],
    [ id ==> next(C), type ==> neutral, in_arg ==> One,
      arcs ==> [ empty : empty => (C < Max -> ask ; otherwise -> over(One)) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  [ calls ==> 0 ]
).

diag_mod(tick,
  [ [ id ==> go, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  [ n ==> 0 ]
).
