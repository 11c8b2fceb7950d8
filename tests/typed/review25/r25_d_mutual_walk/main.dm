% Helper review25 (issue 37, shape d): a walk by mutual recursion of two
% DMs, one call a place: `left(Ps, T)` looks at one place and, if it is not
% the target, calls `right(Rest, T)`, which does the same and calls
% `left`; the final `found(P)` or `missing` is handed back up through every
% level by the exit arcs. The rounds counted by `inc` of a local.
diag_mod(stroll(Rounds, Places, Target),
  [ [ id ==> out,
      type ==> recursive,
      embedded_dm ==> left(Places, Target),
      arcs ==> [ found(_) : [inc(n, K)] => (K >= Rounds -> back ; otherwise -> out),
                 missing : [inc(n, K)] => (K >= Rounds -> back ; otherwise -> out) ]
    ],
    [ id ==> back, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(left(Places, T),
  [ [ id ==> step,
      type ==> neutral,
      arcs ==> [ empty : empty => at(Places) ]
    ],
    [ id ==> at([]),
      type ==> neutral,
      arcs ==> [ empty : empty => missing ]
    ],
    [ id ==> at([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == T -> found(P) ; otherwise -> on(Ps)) ]
    ],
    [ id ==> on(Ps),
      type ==> recursive,
      embedded_dm ==> right(Ps, T),
      arcs ==> [ found(P) : empty => found(P),
                 missing : empty => missing ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> missing, type ==> final ]
  ],
  []
).

diag_mod(right(Places, T),
  [ [ id ==> step,
      type ==> neutral,
      arcs ==> [ empty : empty => at(Places) ]
    ],
    [ id ==> at([]),
      type ==> neutral,
      arcs ==> [ empty : empty => missing ]
    ],
    [ id ==> at([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == T -> found(P) ; otherwise -> on(Ps)) ]
    ],
    [ id ==> on(Ps),
      type ==> recursive,
      embedded_dm ==> left(Ps, T),
      arcs ==> [ found(P) : empty => found(P),
                 missing : empty => missing ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> missing, type ==> final ]
  ],
  []
).
