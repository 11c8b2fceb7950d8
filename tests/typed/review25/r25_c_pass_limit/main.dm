% Helper review25 (issue 37, shape c): the count is the pipe and the limit a
% parameter of the main DM, passed on unchanged to a callee (`hop(Limit)`)
% that passes it on unchanged to its own callee (`edge(L)`); `edge` reads
% the pipe by in_arg, hands it back by out_arg and ends `below` or `reached`;
% the recursive situation adds one by its out_arg after the call.
diag_mod(lap(Limit),
  [ [ id ==> go,
      type ==> recursive,
      in_arg ==> N,
      out_arg ==> N1,
      embedded_dm ==> hop(Limit),
      arcs ==> [ more : [N1 is N + 1] => go,
                 enough : [N1 = N] => stop ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(hop(L),
  [ [ id ==> via,
      type ==> recursive,
      embedded_dm ==> edge(L),
      arcs ==> [ below : empty => more,
                 reached : empty => enough ]
    ],
    [ id ==> more, type ==> final ],
    [ id ==> enough, type ==> final ]
  ],
  []
).

diag_mod(edge(L),
  [ [ id ==> peek,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> X,
      arcs ==> [ empty : empty => (X < L -> below ; otherwise -> reached) ]
    ],
    [ id ==> below, type ==> final ],
    [ id ==> reached, type ==> final ]
  ],
  []
).
