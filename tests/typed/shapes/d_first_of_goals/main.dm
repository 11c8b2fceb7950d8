% Shape (d): the walk stops at the first place that is one of several
% targets (`member(P, Goals)`, the goals a parameter of the walking DM);
% `found(P)` or `not_found`; rounds in the caller's id.
diag_mod(hunt(Rounds, Places, Goals),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> first_goal(Places, Goals),
      arcs ==> [ found(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(first_goal(Places, Goals),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (member(P, Goals) -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
