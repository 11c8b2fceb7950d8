% Shape (c): the limit a global read after each call, compared with `==`;
% the callee's out_arg a constant (the pipe is not the counter).
diag_mod(repeat,
  [ [ id ==> once,
      type ==> recursive,
      embedded_dm ==> unit,
      arcs ==> [ ok : [inc(k, K), get(rounds, R)] => (K == R -> end ; otherwise -> once) ]
    ],
    [ id ==> end, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(unit,
  [ [ id ==> s, type ==> neutral, out_arg ==> served, arcs ==> [ empty : empty => ok ] ],
    [ id ==> ok, type ==> final ]
  ],
  []
).
