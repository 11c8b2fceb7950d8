% visit(Spots, Goal): the goal kept in a local, each spot looked at in a
% situation of its own (`try([S|Ss])`, then `look(S, Ss)`), compared with
% the local read back.
diag_mod(visit(Spots, Goal),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : set(goal, Goal) => try(Spots) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> try([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : empty => look(S, Ss) ]
    ],
    [ id ==> look(S, Ss),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == get(goal, _) -> found(S) ; otherwise -> try(Ss)) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  [ goal ==> none ]
).
