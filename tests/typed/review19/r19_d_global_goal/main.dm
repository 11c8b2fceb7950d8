% Helper review19 (issue 37, shape d): a walk whose element is compared
% with a global read at each visit. `seek(Rounds, Spots, Goal)` stores the
% goal in the global `goal`, then calls `probe(Spots)` each round; `probe`
% walks its list by `at([S|Ss])`, comparing each spot with `get(goal, _)`.
diag_mod(seek(Rounds, Spots, Goal),
  [ [ id ==> setup,
      type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => round ]
    ],
    [ id ==> round,
      type ==> recursive,
      embedded_dm ==> probe(Spots),
      arcs ==> [ hit(_S) : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round),
                 miss : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(probe(Spots),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => at(Spots) ]
    ],
    [ id ==> at([]),
      type ==> neutral,
      arcs ==> [ empty : empty => miss ]
    ],
    [ id ==> at([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == get(goal, _) -> hit(S) ; otherwise -> at(Ss)) ]
    ],
    [ id ==> hit(S), type ==> final ],
    [ id ==> miss, type ==> final ]
  ],
  []
).
