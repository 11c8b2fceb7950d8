% Helper review24 (issue 37, shape c): N calls of `spool`, the limit the
% recursive situation's in_arg; the callee gives two results, the pipe
% handed back by `out_arg ==> L` (L its own in_arg) and the same value
% bound to the caller's variable through its parameter (`diag_mod ==>
% spool(L)`); the caller compares its count (a local) with the second.
diag_mod(winch,
  [ [ id ==> pull,
      type ==> recursive,
      in_arg ==> _Limit,
      embedded_dm ==> spool(Got),
      arcs ==> [ wound : [inc(turns, T)] => (T >= Got -> stowed ; otherwise -> pull),
                 jammed : say(jammed) => stowed ]
    ],
    [ id ==> stowed, type ==> final ]
  ],
  [ turns ==> 0 ]
).

diag_mod(spool(_Out),
  [ [ id ==> reel,
      type ==> neutral,
      in_arg ==> L,
      out_arg ==> L,
      arcs ==> [ empty : empty => (number(L) -> wound ; otherwise -> jammed) ]
    ],
    [ id ==> wound, type ==> final, in_arg ==> L, diag_mod ==> spool(L) ],
    [ id ==> jammed, type ==> final ]
  ],
  []
).
