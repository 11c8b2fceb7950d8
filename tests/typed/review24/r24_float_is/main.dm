% Helper review24: float arithmetic of an arc's action computed natively
% (`codegen/native/float_expr.rs`) and its ways back to the machine: a
% float overflow (`big`), an int subexpression that overflows (`huge`).
diag_mod(scale(X),
  [ [ id ==> s0,
      type ==> neutral,
      arcs ==> [ empty : empty => (X == big -> s1(1.0e308, 0.25) ; otherwise -> s1(1.5, 0.25)) ]
    ],
    [ id ==> s1(V, H),
      type ==> neutral,
      arcs ==> [ empty : [W is V * 10.0 - H, U is -W + H * 2] => (X == huge -> s3(V) ; otherwise -> s2(W, U)) ]
    ],
    [ id ==> s3(V),
      type ==> neutral,
      arcs ==> [ empty : [Z is V + 4611686018427387904 * 4] => s2(Z, Z) ]
    ],
    [ id ==> s2(W, U), type ==> neutral, out_arg ==> [W, U], arcs ==> [ empty : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).
