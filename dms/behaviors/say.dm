% say(Text, Status): the robot says Text (an atom, or a list of words and
% names said as one sentence). Status: ok.
diag_mod(say(Text, _Status),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : say(Text) => success ]
    ],
    [ id ==> success,
      type ==> final,
      diag_mod ==> say(Text, ok)
    ]
  ],
  []
).
