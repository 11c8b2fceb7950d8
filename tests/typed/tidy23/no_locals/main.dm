% Helper tidy23 (issue 37, `--explain-types`' detector): a recursive
% situation of a DM without locals, whose call native code does not push
% (an exit arc's action is a user function): its visit is the runtime's
% hand-over and template in one call (`machine::nat_template`).
diag_mod(main,
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> climb,
      arcs ==> [ up : apply(note(_N), [go]) => roof ]
    ],
    [ id ==> roof, type ==> final ]
  ],
  []
).

diag_mod(climb,
  [ [ id ==> step,
      type ==> neutral,
      arcs ==> [ empty : empty => up ]
    ],
    [ id ==> up, type ==> final ]
  ],
  []
).
