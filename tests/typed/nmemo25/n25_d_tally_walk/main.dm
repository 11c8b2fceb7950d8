% Helper nmemo25 (issue 37, shape d): the walk of `n24_d_note_walk` with
% what was seen so far built at each place (`[S|Seen]`, an accumulator):
% every place calls a DM native code does not push (the exit arc's action
% is a user function, `note/1`), so the walker's frame goes to the machine
% and is entered again at each place, with the rest of the list and the
% accumulator in its id. `survey(Rounds, Places, Want)`.
diag_mod(survey(Rounds, Places, Want),
  [ [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> scan(Places, Want),
      arcs ==> [ found(_) : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask),
                 not_found(_) : [inc(asked, A)] => (A >= Rounds -> closed ; otherwise -> ask) ]
    ],
    [ id ==> closed, type ==> final ]
  ],
  [ asked ==> 0 ]
).

diag_mod(scan(Places, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Places, []) ]
    ],
    [ id ==> visit([], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found(Seen) ]
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
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found(_), type ==> final ]
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
