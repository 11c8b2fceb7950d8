% review17 (issue 37, shape d): the walk announces each spot it passes
% (`note(S)`, an action no effector declares: performed, nothing shown),
% as a robot reporting its progress would. `rounds(N, Spots, Goal)`: a
% round is the call, `is`, a visit a spot, the final.
diag_mod(rounds(N, Spots, Goal),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> patrol(Spots, Goal),
      arcs ==> [ reached(_) : [inc(k, K)] => (K >= N -> stop ; otherwise -> go),
                 lost : [inc(k, K)] => (K >= N -> stop ; otherwise -> go) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(patrol(Spots, Goal),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => at(Spots) ]
    ],
    [ id ==> at([]),
      type ==> neutral,
      arcs ==> [ empty : empty => lost ]
    ],
    [ id ==> at([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : note(S) => (S == Goal -> reached(S) ; otherwise -> at(Ss)) ]
    ],
    [ id ==> reached(_), type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  []
).
