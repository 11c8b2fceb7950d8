% Helper nwinch25 (issue 37): type tests on registers whose MIR type
% decides them (an int count, a float computed by `is`, a list of ints,
% the empty list, an atom) and the empty list asked at run time
% (`atom/1`, `compound/1` of a list, `is_list/1` of an atom).
diag_mod(typed,
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => s(0) ] ],
    [ id ==> s(K),
      type ==> neutral,
      arcs ==> [ empty : [N is K + 1, F is N * 1.5] => probe(N, F, [N, 2], []) ]
    ],
    [ id ==> probe(N, F, L, E),
      type ==> neutral,
      arcs ==> [ empty : [ (integer(N) -> int ; otherwise -> no_int),
                           (float(N) -> float ; otherwise -> no_float),
                           (float(F) -> float ; otherwise -> no_float),
                           (number(F), F > 2 -> big ; otherwise -> small),
                           (is_list(L) -> list ; otherwise -> no_list),
                           (atom(L) -> atom ; otherwise -> no_atom),
                           (compound(L) -> compound ; otherwise -> no_compound),
                           (ground(L) -> ground ; otherwise -> no_ground),
                           (atom(E) -> atom ; otherwise -> no_atom),
                           (is_list(E) -> list ; otherwise -> no_list),
                           (compound(E) -> compound ; otherwise -> no_compound),
                           (\+ atomic(E) -> not_atomic ; otherwise -> atomic) ]
                 => (N < 3 -> s(N) ; otherwise -> last(done)) ]
    ],
    [ id ==> last(A),
      type ==> neutral,
      arcs ==> [ empty : [ (atom(A) -> atom ; otherwise -> no_atom),
                           (is_list(A) -> list ; otherwise -> no_list),
                           (\+ atomic(A) -> not_atomic ; otherwise -> atomic) ]
                 => (atom(A), \+ number(A) -> stop ; otherwise -> last(A)) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).
