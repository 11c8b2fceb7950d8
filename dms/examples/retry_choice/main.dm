% retry_choice: how test-mode input is matched (semantics.md D-14, D-15,
% E2, E3).
%
% * `pick` has two arcs that both unify with p(7): the last one wins.
% * An input that no arc accepts (zz) adds nothing to the history; the
%   same situation is entered again, and its prog runs again (the local
%   `visits` counts both visits).
% * `confirm` has a single arc: after a non-matching input a second term
%   is read at once (E3), and here it matches.
diag_mod(main,
  [
    [ id ==> pick,
      type ==> speech,
      prog ==> [inc(visits, _)],
      arcs ==> [
        p(X) : [one(X)] => confirm,
        p(Y) : [two(Y)] => confirm
      ]
    ],
    [ id ==> confirm,
      type ==> speech,
      prog ==> [inc(visits, _)],
      arcs ==> [
        yes : [get(visits, V), visits(V)] => fs
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  [ visits ==> 0 ]
).
