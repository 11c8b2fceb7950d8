% regrasp(Object, Hand, Result): recovery protocol of `take`. A grasp of
% Object with Hand failed: say so and try once more. Result is what the
% second grasp gave.
diag_mod(regrasp(Object, Hand, _Result),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ say(apply(words(_), [['I could not grasp the', Object, '; I will try again.']])),
                  grasp(Object, Hand, Result) ] => result(Result)
      ]
    ],
    [ id ==> result(R),
      type ==> final,
      diag_mod ==> regrasp(Object, Hand, R)
    ]
  ],
  []
).
