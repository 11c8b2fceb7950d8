% add_ten: adds 10 to the incoming pipe value and pipes the sum back.
diag_mod(add_ten,
  [
    [ id ==> start,
      type ==> neutral,
      in_arg ==> A,
      out_arg ==> B,
      prog ==> [B is A + 10],
      arcs ==> [
        empty : added(A, B) => done
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
