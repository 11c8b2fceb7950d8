% review18 (issue 37, shape (d)): the next situation chosen by a user
% function's result: at each place `route/3` (user_functions.pl) gives the
% next situation, `found(P)` or `walk(Ps)`. `errand(Rounds, Places, Target)`.
diag_mod(errand(Rounds, Places, Target),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> seek(Places, Target),
      arcs ==> [ found(_) : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round),
                 nowhere : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(seek(Places, Target),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => walk(Places) ] ],
    [ id ==> walk([]), type ==> neutral,
      arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> walk([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => apply(route(_, _, _), [P, Ps, Target]) ] ],
    [ id ==> found(_), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
