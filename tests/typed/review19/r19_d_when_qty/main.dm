% Helper review19 (issue 37, shape d): a walk deciding by `when/3` on an
% integer field of `item(Name, Qty)`. `order(Rounds, Items, Need)` calls
% `fill(Items, Need)` each round; `fill` walks `bin([item(N, Q)|Is])` and
% stops at the first item with at least `Need` in stock (`enough(N)`).
diag_mod(order(Rounds, Items, Need),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> fill(Items, Need),
      arcs ==> [ enough(_N) : [inc(done, K)] => (K >= Rounds -> stop ; otherwise -> round),
                 short : [inc(done, K)] => (K >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(fill(Items, Need),
  [ [ id ==> first,
      type ==> neutral,
      arcs ==> [ empty : empty => bin(Items) ]
    ],
    [ id ==> bin([]),
      type ==> neutral,
      arcs ==> [ empty : empty => short ]
    ],
    [ id ==> bin([item(N, Q)|Is]),
      type ==> neutral,
      arcs ==> [ empty : empty => apply(when(_If, _Then, _Else), [Q >= Need, enough(N), bin(Is)]) ]
    ],
    [ id ==> enough(N), type ==> final ],
    [ id ==> short, type ==> final ]
  ],
  []
).
