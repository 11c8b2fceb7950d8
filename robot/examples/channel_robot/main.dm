% The task of the worked example in docs/guide/robot.md: go to the kitchen,
% look at what is there and say it. The status `navigate` binds chooses the
% next situation; `describe/1` is a user function written in Rust.
diag_mod(main,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : navigate(kitchen, Status) => arrived(Status)
      ]
    ],
    [ id ==> arrived(ok),
      type ==> vision,
      arcs ==> [
        objects(Seen) : say(apply(describe(_), [Seen])) => fs
      ]
    ],
    [ id ==> arrived(_Error),
      type ==> neutral,
      arcs ==> [
        empty : say('I could not get to the kitchen.') => fs
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  []
).
