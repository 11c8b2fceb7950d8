% Helper nstock25 (issue 37): lists built cell by cell (`[I|Seen]`) and
% shared: each round's walk keeps the items passed, hands them to the
% final (`kept(Seen)`, read by the caller's next round as its `Before`)
% and starts the next round's list on the last one's cells, so rounds
% hold cells of each other and let them go in any order.
diag_mod(rounds(Rounds, Items, Want),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : empty => pass(0, []) ]
    ],
    [ id ==> pass(N, Before),
      type ==> recursive,
      embedded_dm ==> walk(Items, Want, Before),
      arcs ==> [ kept(Seen) : [M is N + 1] => (M >= Rounds -> done(Seen) ; otherwise -> pass(M, Seen)),
                 hit(Seen) : [M is N + 1] => (M >= Rounds -> done(Seen) ; otherwise -> pass(M, [])) ]
    ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).

diag_mod(walk(Items, Want, Before),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => step(Items, Before) ]
    ],
    [ id ==> step([], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => kept(Seen) ]
    ],
    [ id ==> step([I|Is], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => (I == Want -> hit([I|Seen]) ; otherwise -> step(Is, [I|Seen])) ]
    ],
    [ id ==> kept(_), type ==> final ],
    [ id ==> hit(_), type ==> final ]
  ],
  []
).
