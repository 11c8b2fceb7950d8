% Helper review24 (issue 37, shape d): a walk of integers for the first
% above a cap kept in a global, compared with `<` and `>` in a nested
% guard; three exits: `found(X)`, `not_found`, `error(negative(X))` for a
% reading below zero. The rounds left are the pipe: the recursive
% situation takes them by in_arg and hands the next count on by out_arg.
diag_mod(gauge(Rounds, Readings, Cap),
  [ [ id ==> start,
      type ==> neutral,
      out_arg ==> Rounds,
      arcs ==> [ empty : set(cap, Cap) => watch ]
    ],
    [ id ==> watch,
      type ==> recursive,
      in_arg ==> R,
      out_arg ==> R1,
      embedded_dm ==> probe(Readings),
      arcs ==> [ found(_) : [R1 is R - 1] => (R1 > 0 -> watch ; otherwise -> rest),
                 not_found : [R1 is R - 1] => (R1 > 0 -> watch ; otherwise -> rest),
                 error(E) : say(['bad reading', E]) => rest ]
    ],
    [ id ==> rest, type ==> final ]
  ],
  []
).

diag_mod(probe(Readings),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Readings) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : empty => not_found ]
    ],
    [ id ==> try([X|Xs]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (X < 0 -> error(negative(X))
                   ; otherwise -> (X > get(cap, _) -> found(X) ; otherwise -> try(Xs))) ]
    ],
    [ id ==> found(_), type ==> final ],
    [ id ==> not_found, type ==> final ],
    [ id ==> error(_), type ==> final ]
  ],
  []
).
