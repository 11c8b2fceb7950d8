% Helper review22 (issue 37, shape c): the count in the recursive
% situation's id, `rung(I)`, the next one computed by `is` in the id
% (`rung(_J is I + 1)`); the limit the in_arg, the callee handing it back by
% out_arg.
diag_mod(ladder,
  [ [ id ==> base,
      type ==> neutral,
      arcs ==> [ empty : empty => rung(1) ]
    ],
    [ id ==> rung(I),
      type ==> recursive,
      in_arg ==> Top,
      embedded_dm ==> climb,
      arcs ==> [ up : empty => (I >= Top -> roof ; otherwise -> rung(_J is I + 1)) ]
    ],
    [ id ==> roof, type ==> final ]
  ],
  []
).

diag_mod(climb,
  [ [ id ==> step,
      type ==> neutral,
      in_arg ==> H,
      out_arg ==> H,
      arcs ==> [ empty : empty => up ]
    ],
    [ id ==> up, type ==> final ]
  ],
  []
).
