% Workload (d) of issue 37: N rounds of a call `search(Places, Target)` that
% walks a list of atoms by the compound id `try([P|Ps])`, compares each with
% the target and ends in `found(P)` or `not_found`, which the caller's exit
% arcs match. `main(Rounds, Places, Target)`: with the target last in a list
% of 8, a round is 11 transitions (the call, `is`, 8 visits of `try`, the
% final situation).
diag_mod(main(Rounds, Places, Target),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> search(Places, Target),
      arcs ==> [ found(P) : [inc(n, N)] => (N >= Rounds -> fs ; otherwise -> round),
                 not_found : [inc(n, N)] => (N >= Rounds -> fs ; otherwise -> round) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(search(Places, Target),
  [ [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Places) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
