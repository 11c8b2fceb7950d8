% A list walk whose out_arg is a user function that fails on one element
% (the tests' `is_bed(_)` on `boom`): the error names the situation's id
% `try([boom, ...])`, which native code builds only for the error (or
% for the history), after the next situation took the list's rest.
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
      out_arg ==> apply(is_bed(_), [P]),
      arcs ==> [ empty : empty => (P == bed -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
