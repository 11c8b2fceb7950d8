% Shape (c): the callee computes its out_arg by a Prolog user function
% (`apply(succ_of(_), [X])`, X its in_arg), the caller reads the pipe on
% a neutral situation and compares it with its parameter by `<`.
% `relay(Max)` makes Max calls of `succ` (at least one).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask,
      type ==> recursive,
      embedded_dm ==> succ,
      arcs ==> [ added : empty => test ]
    ],
    [ id ==> test,
      type ==> neutral,
      in_arg ==> V,
      arcs ==> [ empty : empty => (V < Max -> ask ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(succ,
  [ [ id ==> add,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> apply(succ_of(_), [X]),
      arcs ==> [ empty : empty => added ]
    ],
    [ id ==> added, type ==> final ]
  ],
  []
).
