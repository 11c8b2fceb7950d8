% Helper review19 (issue 37, shape d): a list of lists. `pick(Rounds,
% Shelves, Want)` walks shelves (each a list of items) and the items of
% each shelf, two compound ids, until an item equals `Want`; the callee ends
% in `got(Item)` or `none`, which the caller's exit arcs match.
diag_mod(pick(Rounds, Shelves, Want),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> aisle(Shelves, Want),
      arcs ==> [ got(_I) : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round),
                 none : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(aisle(Shelves, Want),
  [ [ id ==> enter,
      type ==> neutral,
      arcs ==> [ empty : empty => shelf(Shelves) ]
    ],
    [ id ==> shelf([]),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> shelf([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : empty => item(S, Ss) ]
    ],
    [ id ==> item([], Ss),
      type ==> neutral,
      arcs ==> [ empty : empty => shelf(Ss) ]
    ],
    [ id ==> item([I|Is], Ss),
      type ==> neutral,
      arcs ==> [ empty : empty => (I == Want -> got(I) ; otherwise -> item(Is, Ss)) ]
    ],
    [ id ==> got(I), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
