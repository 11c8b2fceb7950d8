% review18 (issue 37, shape (d)): a walk over an inventory of compounds
% `item(Name, Qty)`, looking for `Want` and adding up the quantities of the
% items before it; ends in `have(Qty, Before)` or `none(Total)`, which the
% caller's exit arcs match. `stock(Rounds, Items, Want)`.
diag_mod(stock(Rounds, Items, Want),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> count(Items, Want),
      arcs ==> [ have(_, _) : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round),
                 none(_) : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(count(Items, Want),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => look(Items, 0) ] ],
    [ id ==> look([], Sum), type ==> neutral,
      arcs ==> [ empty : empty => none(Sum) ] ],
    [ id ==> look([item(Name, Qty)|Rest], Sum), type ==> neutral,
      arcs ==> [ empty : [Sum1 is Sum + Qty] =>
                   (Name == Want -> have(Qty, Sum) ; otherwise -> look(Rest, Sum1)) ] ],
    [ id ==> have(_, _), type ==> final ],
    [ id ==> none(_), type ==> final ]
  ],
  []
).
