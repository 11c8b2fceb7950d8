% Helper nmemo25 (issue 37): accumulators handed between native code and
% the machine at every place (the exit arc's action is a user function,
% `note/1`, so each visit goes through the machine and the frame is
% entered again). `pair`: two lists built on the same tail at each place
% (`[S|Seen]` and `[x|Seen]`), handed back by the final. `bound`: an
% accumulator whose last cell is a variable bound later (when the walk
% ends, by the id `close(Seen, [])`), then walked again.
diag_mod(pair(Places, Want),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> twins(Places, Want, _, _),
      arcs ==> [ found(A, B) : empty => done(found, A, B),
                 missing(A, B) : empty => done(missing, A, B) ]
    ],
    [ id ==> done(_, _, _), type ==> final ]
  ],
  []
).

diag_mod(twins(Places, Want, _Seen, _Alt),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Places, [], []) ]
    ],
    [ id ==> visit([], Seen, Alt),
      type ==> neutral,
      arcs ==> [ empty : empty => missing(Seen, Alt) ]
    ],
    [ id ==> visit([P|Ps], Seen, Alt),
      type ==> recursive,
      embedded_dm ==> probe(P),
      arcs ==> [ seen(S) : apply(note(_), [S]) => check(S, Ps, [S|Seen], [S|Alt]) ]
    ],
    [ id ==> check(S, Ps, Seen, Alt),
      type ==> neutral,
      arcs ==> [ empty : empty => (S == Want -> found(Seen, Alt) ; otherwise -> visit(Ps, Seen, [x|Seen])) ]
    ],
    [ id ==> found(Seen, Alt), type ==> final, diag_mod ==> twins(Places, Want, Seen, Alt) ],
    [ id ==> missing(Seen, Alt), type ==> final, diag_mod ==> twins(Places, Want, Seen, Alt) ]
  ],
  []
).

diag_mod(bound(Places, Want),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => visit(Places, [start|T], T) ]
    ],
    [ id ==> visit([], Seen, T),
      type ==> neutral,
      arcs ==> [ empty : empty => close(Seen, T) ]
    ],
    [ id ==> visit([P|Ps], Seen, T),
      type ==> recursive,
      embedded_dm ==> probe(P),
      arcs ==> [ seen(S) : apply(note(_), [S]) => visit(Ps, [S|Seen], T) ]
    ],
    [ id ==> close(Seen, []),
      type ==> neutral,
      arcs ==> [ empty : empty => again(Seen) ]
    ],
    [ id ==> again([]),
      type ==> neutral,
      arcs ==> [ empty : empty => missing ]
    ],
    [ id ==> again([Q|Qs]),
      type ==> recursive,
      embedded_dm ==> probe(Q),
      arcs ==> [ seen(S) : apply(note(_), [S]) => (S == Want -> found(Qs) ; otherwise -> again(Qs)) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> missing, type ==> final ]
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
