% Helper review22 (issue 37, shape c): N calls of `stage` (its own file),
% the budget the recursive situation's in_arg, the callee handing the pipe
% back by `out_arg ==> Fuel`; the calls counted in a global; three exit
% arcs (the last a catch-all no final reaches).
diag_mod(launch,
  [ [ id ==> fire,
      type ==> recursive,
      in_arg ==> Budget,
      embedded_dm ==> stage,
      arcs ==> [ lit : [inc(fired, F)] => (F >= Budget -> landed ; otherwise -> fire),
                 dud : empty => scrubbed,
                 Other : say(['odd stage', Other]) => scrubbed ]
    ],
    [ id ==> landed, type ==> final ],
    [ id ==> scrubbed, type ==> final ]
  ],
  []
).
