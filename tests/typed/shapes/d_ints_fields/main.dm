% Shape (d): a list of ints, the first above a threshold, its position
% counted in the id (`scan([N|Ns], I)`); the final `hit(N, I)` has two
% fields; the caller's rounds a local compared with `>`.
diag_mod(rounds(Times),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> first_above([3, 1, 4, 1, 5, 9, 2, 6], 8),
      arcs ==> [ hit(N, At) : [inc(done, D)] => (Times > D -> round ; otherwise -> out),
                 miss : [inc(done, D)] => (Times > D -> round ; otherwise -> out) ]
    ],
    [ id ==> out, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(first_above(Ns, T),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => scan(Ns, 0) ] ],
    [ id ==> scan([], _), type ==> neutral, arcs ==> [ empty : empty => miss ] ],
    [ id ==> scan([N|Rest], I),
      type ==> neutral,
      arcs ==> [ empty : [J is I + 1] => (N > T -> hit(N, I) ; otherwise -> scan(Rest, J)) ]
    ],
    [ id ==> hit(N, I), type ==> final ],
    [ id ==> miss, type ==> final ]
  ],
  []
).
