% Helper nglob24 (issue 37): a global list native code reads and writes
% (`get` then `set`, its copy kept as a Rust value) that the machine also
% writes between two native visits (`assign` then `set`: the machine's
% evaluator). Every native read after the machine's write must see it.
diag_mod(mix(Budget),
  [ [ id ==> pick,
      type ==> neutral,
      arcs ==> [ empty : [get(seen, S), inc(count, C), set(seen, [C|S])]
                   => (C >= Budget -> check ; otherwise -> other(C)) ]
    ],
    [ id ==> other(C),
      type ==> neutral,
      arcs ==> [ empty : [assign(S, get(seen, _)), set(seen, [C|S])] => pick ]
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
