% Helper review19 (issue 37, shape d): a walk stopping at the first element
% a Prolog user function accepts. `weigh(Rounds, Crates)` calls
% `scale(Crates)` each round; `scale` asks `heavy/1` of each crate's weight
% and ends in `heavy(W)` or `light`.
diag_mod(weigh(Rounds, Crates),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> scale(Crates),
      arcs ==> [ heavy(_W) : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round),
                 light : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(scale(Crates),
  [ [ id ==> load,
      type ==> neutral,
      arcs ==> [ empty : empty => crate(Crates) ]
    ],
    [ id ==> crate([]),
      type ==> neutral,
      arcs ==> [ empty : empty => light ]
    ],
    [ id ==> crate([W|Ws]),
      type ==> neutral,
      arcs ==> [ empty : empty => (apply(heavy(_X), [W]) == yes -> heavy(W) ; otherwise -> crate(Ws)) ]
    ],
    [ id ==> heavy(W), type ==> final ],
    [ id ==> light, type ==> final ]
  ],
  []
).
