% Shape (c): a call with three arguments, the last an output bound by the
% callee's final `diag_mod`; the caller walks by the compound id
% `loop(I)` with the limit a parameter, `>=`.
diag_mod(steps(Max),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => loop(0) ] ],
    [ id ==> loop(I),
      type ==> recursive,
      embedded_dm ==> add(I, 1, J),
      arcs ==> [ sum(_) : empty => (J >= Max -> fin ; otherwise -> loop(J)) ]
    ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

diag_mod(add(A, B, C),
  [ [ id ==> calc, type ==> neutral,
      arcs ==> [ empty : [S is A + B] => sum(S) ] ],
    [ id ==> sum(S), type ==> final, diag_mod ==> add(A, B, S) ]
  ],
  []
).
