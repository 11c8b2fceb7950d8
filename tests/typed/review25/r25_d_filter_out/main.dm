% Helper review25 (issue 37, shape d): a callee whose in_arg is a list and
% whose out_arg is the list filtered (the stops that are not `Drop`, kept
% in an accumulator in the walk's id, last first); the caller puts the list
% in the pipe by out_arg, and reads the filtered one by the in_arg of the
% situation after the call, which ends the run with it.
diag_mod(sweep(Rounds, Stops, Drop),
  [ [ id ==> load,
      type ==> neutral,
      out_arg ==> Stops,
      arcs ==> [ empty : empty => sort ]
    ],
    [ id ==> sort,
      type ==> recursive,
      embedded_dm ==> keep(Drop),
      arcs ==> [ kept : empty => check ]
    ],
    [ id ==> check,
      type ==> neutral,
      in_arg ==> Kept,
      out_arg ==> Stops,
      arcs ==> [ empty : [inc(n, N)] => (N >= Rounds -> done(Kept) ; otherwise -> sort) ]
    ],
    [ id ==> done(_), type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(keep(Drop),
  [ [ id ==> begin,
      type ==> neutral,
      in_arg ==> L,
      arcs ==> [ empty : empty => walk(L, []) ]
    ],
    [ id ==> walk([], Acc),
      type ==> neutral,
      out_arg ==> Acc,
      arcs ==> [ empty : empty => kept ]
    ],
    [ id ==> walk([P|Ps], Acc),
      type ==> neutral,
      arcs ==> [ empty : empty => (P \== Drop -> walk(Ps, [P|Acc]) ; otherwise -> walk(Ps, Acc)) ]
    ],
    [ id ==> kept, type ==> final ]
  ],
  []
).
