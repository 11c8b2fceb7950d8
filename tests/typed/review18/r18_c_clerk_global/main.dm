% review18 (issue 37, shape (c)): the callee decides. `boss(Max)` calls
% `clerk(Max)` until the clerk says `enough(S)`: the clerk counts the
% customers served in a global (kept across the calls), compares it with the
% limit it was called with, and ends in `more` or `enough(S)`, which the
% caller's exit arcs match. N calls, the last one's count in the final id.
diag_mod(boss(Max),
  [ [ id ==> ask, type ==> recursive, embedded_dm ==> clerk(Max),
      arcs ==> [ more : empty => ask,
                 enough(S) : empty => done(S) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).

diag_mod(clerk(Limit),
  [ [ id ==> serve, type ==> neutral,
      arcs ==> [ empty : [inc(served, S)] =>
                   (S >= Limit -> enough(S) ; otherwise -> more) ] ],
    [ id ==> more, type ==> final ],
    [ id ==> enough(_), type ==> final ]
  ],
  []
).
