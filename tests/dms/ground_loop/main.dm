% A ground DM that never ends: one neutral situation whose action is the
% atom `tick`. The allocation test stops it from its Actions after enough
% transitions (`fs` is never reached).
diag_mod(main,
  [
    [ id ==> spin,
      type ==> neutral,
      arcs ==> [ empty : tick => spin ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  []
).
