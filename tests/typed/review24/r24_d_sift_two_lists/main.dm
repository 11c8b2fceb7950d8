% Helper review24 (issue 37, shape d): the walker's recursive situation has
% a compound id of two lists, the items to go and those passed
% (`step([I|Is], Passed)`); each item is compared by a DM of its own
% (`same(I, Want)`, a call inside the callee) whose final `yes` or `no`
% the walker's exit arcs take; the elements quoted atoms with spaces.
diag_mod(sort_room(Rounds, Items, Want),
  [ [ id ==> open,
      type ==> neutral,
      arcs ==> [ empty : empty => pass(0) ]
    ],
    [ id ==> pass(I),
      type ==> recursive,
      embedded_dm ==> sift(Items, Want),
      arcs ==> [ hit(_, _) : [J is I + 1] => (J >= Rounds -> tidy ; otherwise -> pass(J)),
                 miss(_) : [J is I + 1] => (J >= Rounds -> tidy ; otherwise -> pass(J)) ]
    ],
    [ id ==> tidy, type ==> final ]
  ],
  []
).

diag_mod(sift(Items, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => step(Items, []) ]
    ],
    [ id ==> step([], Passed),
      type ==> neutral,
      arcs ==> [ empty : empty => miss(Passed) ]
    ],
    [ id ==> step([I|Is], Passed),
      type ==> recursive,
      embedded_dm ==> same(I, Want),
      arcs ==> [ yes : empty => hit(I, Passed),
                 no : empty => step(Is, [I|Passed]) ]
    ],
    [ id ==> hit(_, _), type ==> final ],
    [ id ==> miss(_), type ==> final ]
  ],
  []
).

diag_mod(same(A, B),
  [ [ id ==> cmp,
      type ==> neutral,
      arcs ==> [ empty : empty => (A == B -> yes ; otherwise -> no) ]
    ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).
