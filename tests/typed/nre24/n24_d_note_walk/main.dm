% Helper nre24 (issue 37, shape d): a walk whose every step calls a DM that
% native code does not push (the exit arc's action is a user function,
% `note/1`: the machine runs the visit from its template), then a situation
% that runs natively: the walker's frame is entered again from the machine
% at each place, with the list in its parameter (`Places`) and in its id
% (`Ps`). `survey(Rounds, Places, Want)`.
diag_mod(survey(Rounds, Places, Want),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> scan(Places, Want),
      arcs ==> [ found(_) : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask),
                 not_found : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask) ]
    ],
    [ id ==> closed, type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(scan(Places, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Places) ]
    ],
    [ id ==> visit([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> visit([P|Ps]),
      type ==> recursive,
      embedded_dm ==> probe(P),
      arcs ==> [ seen(S) : apply(note(_), [S]) => check(S, Ps) ]
    ],
    [ id ==> check(S, Ps),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == Want -> found(S) ; otherwise -> visit(Ps)) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).

diag_mod(probe(P),
  [ [ id ==> look,
      type ==> neutral,
      arcs ==> [ empty : empty => seen(P) ]
    ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).
