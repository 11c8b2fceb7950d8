% Shape (c): the callee's out_arg a conditional on its in_arg (7 when it is
% positive, else 1), read back by the caller on a neutral situation and
% compared with a local limit (the pipe's value, not the conditional's text).
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
  [ limit ==> 3 ]
).

diag_mod(succ,
  [ [ id ==> add,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> (X > 0 -> 7 ; otherwise -> 1),
      arcs ==> [ empty : empty => next ]
    ],
    [ id ==> next, type ==> final ]
  ],
  []
).
