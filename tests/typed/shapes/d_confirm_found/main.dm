% Shape (d): the walk's found situation is recursive: it asks for
% confirmation through a DM whose one step is neutral (no input), `yes`
% ends the walk in `found(P)`, `no` goes on with the rest, carried in the
% id `confirm(P, Ps)`; the target a parameter of the walking DM.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> seek(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(seek(L, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(L) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == T -> confirm(P, Ps) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> confirm(P, Ps),
      type ==> recursive,
      embedded_dm ==> sure(P),
      arcs ==> [ yes : empty => found(P), no : empty => try(Ps) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).

diag_mod(sure(P),
  [ [ id ==> ask, type ==> neutral,
      arcs ==> [ empty : empty => (P == unknown -> no ; otherwise -> yes) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).
