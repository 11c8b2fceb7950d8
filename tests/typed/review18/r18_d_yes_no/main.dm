% review18 (issue 37, shape (d), perception): a walk over places asking the
% user at each one whether the cup is there; a scripted user answers `yes.`
% or `no.`. `ask(Rounds, Places)`: each round walks until a `yes` (then
% `found(P)`) or the end of the list (`nowhere`).
diag_mod(ask(Rounds, Places),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> quiz(Places),
      arcs ==> [ found(_) : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round),
                 nowhere : [inc(n, K)] => (K >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(quiz(Places),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => q(Places) ] ],
    [ id ==> q([]), type ==> neutral,
      arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> q([P|Ps]), type ==> listening,
      arcs ==> [ said(yes) : empty => found(P),
                 said(no) : empty => q(Ps) ] ],
    [ id ==> found(_), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
