% A list walk whose comparison is a user function that fails on one
% element (the tests' `is_bed(_)` on `boom`): the error names the
% situation's id `try([boom, ...])`, built only for the error in native
% code.
diag_mod(main(Places),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> search(Places),
      arcs ==> [ found(P) : empty => fin(P), not_found : empty => fin(none) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(search(Places),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(is_bed(_), [P]) == yes -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
