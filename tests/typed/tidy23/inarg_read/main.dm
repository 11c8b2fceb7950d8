% Helper tidy23 (issue 37, `--explain-types`' detector): a recursive
% situation whose in_arg is read (`Top`, the exit arc's limit) and
% whose call native code does not push (an exit arc's action is a user
% function): its visit converts the pipe, then runs the
% template (review22's finding 1's shape).
diag_mod(main,
  [ [ id ==> base,
      type ==> neutral,
      out_arg ==> 3,
      arcs ==> [ empty : empty => rung(1) ]
    ],
    [ id ==> rung(I),
      type ==> recursive,
      in_arg ==> Top,
      embedded_dm ==> climb,
      arcs ==> [ up : apply(note(_N), [I]) => (I >= Top -> roof ; otherwise -> rung(_J is I + 1)) ]
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
