% ask(Topic): one question; ends in got(Answer), or failed on `dunno`.
% The pipe becomes the topic asked about.
diag_mod(ask(Topic),
  [
    [ id ==> is,
      type ==> speech,
      out_arg ==> Topic,
      prog ==> [inc(asked, _)],
      arcs ==> [
        answer(A) : [say(Topic)] => got(A),
        dunno : [] => failed
      ]
    ],
    [ id ==> got(_), type ==> final ],
    [ id ==> failed, type ==> final ]
  ],
  []
).
