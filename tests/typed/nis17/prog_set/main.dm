% nis17 (issue 37): a `prog` of `set`s of locals to constants, run at
% each entry of its situation; the walk re-enters it
% while its count is below `N`. (A prog naming a parameter runs on a copy,
% D-10, and stays term code.)
diag_mod(stock(Item, N),
  [ [ id ==> fill,
      type ==> neutral,
      prog ==> [ set(shelf, [a, b, c]), set(last, shelf) ],
      arcs ==> [ empty : empty => look(get(shelf, _)) ]
    ],
    [ id ==> look([]),
      type ==> neutral,
      arcs ==> [ empty : [inc(seen, V)] => (V < N -> fill ; otherwise -> gone(get(last, _))) ]
    ],
    [ id ==> look([S|Ss]),
      type ==> neutral,
      arcs ==> [ empty : [inc(seen, V)] => (S == Item -> got(V) ; otherwise -> look(Ss)) ]
    ],
    [ id ==> got(_), type ==> final ],
    [ id ==> gone(_), type ==> final ]
  ],
  [ shelf ==> [], last ==> none, seen ==> 0 ]
).
