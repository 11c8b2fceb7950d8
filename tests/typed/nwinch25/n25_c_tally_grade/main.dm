% Helper nwinch25 (issue 37, shape c): N calls of `grade`, N the pipe the
% main DM starts with. `grade` decides the pipe's kind by type tests
% (`integer(X), X > 0`, `float(X)`) and hands the value back through its
% parameter from two of its three finals (`whole`, `frac`); `other`
% leaves the caller's `Cap` unbound, and the caller's arc for it does not
% read it. The caller counts its rounds in a local against `Cap`.
diag_mod(tally,
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> grade(Cap),
      arcs ==> [ whole : [inc(count, C)] => (C >= Cap -> done ; otherwise -> round),
                 frac : [inc(count, C)] => (C >= Cap -> done ; otherwise -> round),
                 other : say(not_a_number) => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ count ==> 0 ]
).

diag_mod(grade(_Cap),
  [ [ id ==> look,
      type ==> neutral,
      in_arg ==> X,
      arcs ==> [ empty : empty =>
                   (integer(X), X > 0 -> whole ; otherwise -> (float(X) -> frac ; otherwise -> other)) ]
    ],
    [ id ==> whole, type ==> final, in_arg ==> X, diag_mod ==> grade(X) ],
    [ id ==> frac, type ==> final, in_arg ==> X, diag_mod ==> grade(X) ],
    [ id ==> other, type ==> final ]
  ],
  []
).
