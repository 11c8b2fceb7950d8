% Shape (d) with an accumulator: `look([P|Ps], Seen)` goes to
% `look(Ps, [P|Seen])`; the final `found(P, Seen)` hands back the places
% passed; the caller matches `found(P, _)` and `not_found(_)`.
diag_mod(survey(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> scan(Places, Target),
      arcs ==> [ found(P, _) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 not_found(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(scan(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => look(Places, []) ] ],
    [ id ==> look([], Seen), type ==> neutral, arcs ==> [ empty : empty => not_found(Seen) ] ],
    [ id ==> look([P|Ps], Seen),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P, Seen) ; otherwise -> look(Ps, [P|Seen])) ]
    ],
    [ id ==> found(P, Seen), type ==> final ],
    [ id ==> not_found(Seen), type ==> final ]
  ],
  []
).
