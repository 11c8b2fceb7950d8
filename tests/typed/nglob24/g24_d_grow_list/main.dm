% Helper nglob24 (issue 37): a global list grown by one element a step and
% read at each step (`seen`: `get`, then `set` of one element more, as the
% apps accumulate), and an int counter global (`count`, by `inc`): Budget
% steps of one situation; the list read back at the end.
diag_mod(gather(Budget),
  [ [ id ==> pick,
      type ==> neutral,
      arcs ==> [ empty : [get(seen, S), inc(count, C), set(seen, [C|S])]
                   => (C >= Budget -> check ; otherwise -> pick) ]
    ],
    [ id ==> check,
      type ==> neutral,
      arcs ==> [ empty : empty => (get(seen, _) == [] -> lost ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ],
    [ id ==> lost, type ==> final ]
  ],
  []
).
