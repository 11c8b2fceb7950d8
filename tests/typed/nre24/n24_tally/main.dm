% Helper nre24 (issue 37): walks whose every step calls a DM that native
% code does not push (the exit arc's action is a user function, `note/1`),
% then a situation that runs natively, entered again from the machine at
% each place: the list in the parameter and in the id, what was seen so
% far built at each place on the list the machine handed back (`[S|Seen]`)
% and handed back by the final as an output argument (`tally`); integers
% compared with a limit (`over`).
diag_mod(report(Places, Want),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> tally(Places, Want, _),
      arcs ==> [ found(Seen) : empty => done(found, Seen),
                 missing(Seen) : empty => done(missing, Seen) ]
    ],
    [ id ==> done(_, _), type ==> final ]
  ],
  []
).

diag_mod(tally(Places, Want, _Seen),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Places, []) ]
    ],
    [ id ==> visit([], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => missing(Seen) ]
    ],
    [ id ==> visit([P|Ps], Seen),
      type ==> recursive,
      embedded_dm ==> probe(P),
      arcs ==> [ seen(S) : apply(note(_), [S]) => check(S, Ps, [S|Seen]) ]
    ],
    [ id ==> check(S, Ps, Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == Want -> found(Seen) ; otherwise -> visit(Ps, Seen)) ]
    ],
    [ id ==> found(Seen), type ==> final, diag_mod ==> tally(Places, Want, Seen) ],
    [ id ==> missing(Seen), type ==> final, diag_mod ==> tally(Places, Want, Seen) ]
  ],
  []
).

diag_mod(over(Ints, Limit),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Ints) ]
    ],
    [ id ==> visit([]),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> visit([I|Is]),
      type ==> recursive,
      embedded_dm ==> probe(I),
      arcs ==> [ seen(S) : apply(note(_), [S]) => weigh(S, Is) ]
    ],
    [ id ==> weigh(S, Is),
      type ==> neutral,
      arcs ==> [ empty : empty => (S > Limit -> above(S, Is) ; otherwise -> visit(Is)) ]
    ],
    [ id ==> above(_, _), type ==> final ],
    [ id ==> none, type ==> final ]
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
