% ask(Topic, Result): asks about Topic at most twice. Result is bound by
% the diag_mod attribute of the final situation reached: to the answer
% given, or to `none` when the user did not know twice (so the head
% variable is used only through that binding). Every question asked counts
% in the global `tries`.
diag_mod(ask(Topic, _Result),
  [
    [ id ==> is,
      type ==> speech,
      prog ==> [inc(tries, _)],
      arcs ==> [
        answer(A) : [screen(Topic)] => got(A),
        dunno : [screen('once more')] => again
      ]
    ],
    [ id ==> again,
      type ==> speech,
      prog ==> [inc(tries, _)],
      arcs ==> [
        answer(A) : [] => got(A),
        dunno : [] => failed
      ]
    ],
    [ id ==> got(A),
      type ==> final,
      diag_mod ==> ask(Topic, A)
    ],
    [ id ==> failed,
      type ==> final,
      diag_mod ==> ask(Topic, none)
    ]
  ],
  []
).
