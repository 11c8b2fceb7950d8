% Helper review24 (issue 37, shape d): a walk of pairs `Name-Place`
% searched by the first part, the pair taken apart in the compound id
% (`look([N-P|Rest])`); the place of the one found is said by the
% caller's exit arc (`say([found, Who, at, P])`) once a round, not a step;
% the rounds counted in a local.
diag_mod(where(Rounds, People, Who),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> locate(People, Who),
      arcs ==> [ at(P) : [say([found, Who, at, P]), inc(asked, A)] => (A >= Rounds -> done ; otherwise -> ask),
                 nowhere : [inc(asked, A)] => (A >= Rounds -> done ; otherwise -> ask) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(locate(People, Who),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => look(People) ]
    ],
    [ id ==> look([]),
      type ==> neutral,
      arcs ==> [ empty : empty => nowhere ]
    ],
    [ id ==> look([N-P|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => (N == Who -> at(P) ; otherwise -> look(Rest)) ]
    ],
    [ id ==> at(_), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
