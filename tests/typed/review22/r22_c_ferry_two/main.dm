% Helper review22 (issue 37, shape c): the recursion goes through two
% situations (`depart` calls, `tally` counts in a local and goes back);
% the limit is `depart`'s in_arg, passed to the callee as its argument
% too, and the callee hands the pipe back by out_arg and ends in
% `docked(L)`, which the caller's exit arc takes apart.
diag_mod(shuttle,
  [ [ id ==> depart,
      type ==> recursive,
      in_arg ==> Trips,
      embedded_dm ==> ferry(Trips),
      arcs ==> [ docked(T) : empty => tally(T) ]
    ],
    [ id ==> tally(T),
      type ==> neutral,
      arcs ==> [ empty : [inc(trips_done, D)] => (D < T -> depart ; otherwise -> moored) ]
    ],
    [ id ==> moored, type ==> final ]
  ],
  [ trips_done ==> 0 ]
).

diag_mod(ferry(_Limit),
  [ [ id ==> sail,
      type ==> neutral,
      in_arg ==> L,
      out_arg ==> L,
      arcs ==> [ empty : empty => docked(L) ]
    ],
    [ id ==> docked(_), type ==> final ]
  ],
  []
).
