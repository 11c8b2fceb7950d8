% Shape (d): the target matched in the walk's id rather than compared:
% `try([T|_], T)` is selected when the head is the target, `try([_|Ps], T)`
% otherwise (source order, D-21); `found(T)` or `not_found`.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> search(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(search(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places, Target) ] ],
    [ id ==> try([], _), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([T|_], T), type ==> neutral, arcs ==> [ empty : empty => found(T) ] ],
    [ id ==> try([_|Ps], T), type ==> neutral, arcs ==> [ empty : empty => try(Ps, T) ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
