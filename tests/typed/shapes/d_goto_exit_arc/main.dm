% Shape (d): the robot goes to each place in turn (`goto(P)`, a DM that
% ends in `arrived(Where)`), and the walking situation's exit arc compares
% the place reached with the target, the walking DM's parameter:
% `arrived(Q) : empty => (Q == Target -> found(Q) ; otherwise -> visit(Ps))`;
% rounds in the caller's id.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> tour(Places, Target),
      arcs ==> [ found(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(tour(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => visit(Places) ] ],
    [ id ==> visit([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> visit([P|Ps]),
      type ==> recursive,
      embedded_dm ==> goto(P),
      arcs ==> [ arrived(Q) : empty => (Q == Target -> found(Q) ; otherwise -> visit(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).

diag_mod(goto(Place),
  [ [ id ==> move, type ==> neutral, arcs ==> [ empty : empty => arrived(Place) ] ],
    [ id ==> arrived(Where), type ==> final ]
  ],
  []
).
