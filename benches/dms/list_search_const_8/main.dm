% Workload (d) of issue 37 with the call's arguments constants
% (`search([p0, ..., p7], p7)`, 8 places, the target last): the MIR's
% inference types `search`'s parameters (list<sym>, sym), so its body runs
% as native code (`codegen::native`), which `benches/dms/list_search` (the
% places from the command line, typed `term`) does not yet. `main(Rounds)`:
% a round is 11 transitions (the call, `is`, 8 visits of `try`, the final
% situation).
diag_mod(main(Rounds),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> search([
          p0, p1, p2, p3, p4, p5, p6, p7
        ], p7),
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
