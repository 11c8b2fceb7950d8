% Helper tidy23 (issue 37, `--explain-types`' detector): a recursive
% situation of a DM with a local, whose call native code does not push
% (an exit arc's action is a user function): its visit hands the native
% frames over (the local written back), then runs the template.
diag_mod(main,
  [ [ id ==> rung(I),
      type ==> recursive,
      embedded_dm ==> climb,
      arcs ==> [ up : [apply(note(_N), [I]), set(steps, I)] => (I >= 3 -> roof ; otherwise -> rung(_J is I + 1)) ]
    ],
    [ id ==> roof, type ==> final ]
  ],
  [ steps ==> 0 ]
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
