% review18 (issue 37, shape (d)): where is the object? A walk over a list of
% pairs `Room-Object`; the object sought is matched in the situation's id
% (the same variable twice), the room handed back in the final's id, and the
% caller compares it with the room it expects. `tidy(Rounds, Pairs, Obj, Home)`.
diag_mod(tidy(Rounds, Pairs, Obj, Home),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> where(Pairs, Obj),
      arcs ==> [ in(R) : [inc(n, K)] =>
                   (K >= Rounds -> fs(R) ; otherwise -> (R == Home -> round ; otherwise -> moved(R))),
                 lost : [inc(n, K)] => (K >= Rounds -> fs(lost) ; otherwise -> round) ] ],
    [ id ==> moved(R), type ==> neutral,
      arcs ==> [ empty : [say(R)] => round ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(where(Pairs, Obj),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => scan(Pairs, Obj) ] ],
    [ id ==> scan([], _), type ==> neutral,
      arcs ==> [ empty : empty => lost ] ],
    [ id ==> scan([Room-O|_], O), type ==> neutral,
      arcs ==> [ empty : empty => in(Room) ] ],
    [ id ==> scan([_|Rest], O), type ==> neutral,
      arcs ==> [ empty : empty => scan(Rest, O) ] ],
    [ id ==> in(_), type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  []
).
