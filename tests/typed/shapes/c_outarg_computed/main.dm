% Shape (c): the callee computes its out_arg (`Y is X + 1`), the caller
% reads the pipe on a neutral situation and compares it with a local
% limit by `=<`.
diag_mod(loop,
  [ [ id ==> call,
      type ==> recursive,
      embedded_dm ==> succ,
      arcs ==> [ next : empty => test ]
    ],
    [ id ==> test,
      type ==> neutral,
      in_arg ==> V,
      arcs ==> [ empty : [get(limit, L)] => (V =< L -> call ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ limit ==> 300 ]
).

diag_mod(succ,
  [ [ id ==> add,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> Y,
      prog ==> [Y is X + 1],
      arcs ==> [ empty : empty => next ]
    ],
    [ id ==> next, type ==> final ]
  ],
  []
).
