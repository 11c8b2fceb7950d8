% nis17 (issue 37): a `prog` of `inc`s of an int local (one with `_`, one
% with a variable of the prog only), run at each entry of its situation,
% the local starting near the top of `i64`: the machine's error where it
% overflows.
diag_mod(count(N),
  [ [ id ==> go,
      type ==> neutral,
      prog ==> [ inc(c, _), inc(c, V) ],
      arcs ==> [ empty : empty => (get(c, _) >= N -> stop ; otherwise -> go) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ c ==> 9223372036854775790 ]
).
