% The debugger's test application (Appendix-A-like, written for the
% tests): `main` is greeted, asks about a colour through the embedded DM
% `ask`, keeps the answer in its local `color`, and counts greetings in
% the local `visits`; `ask` counts its questions in the global `asked`.
% `go(S)` jumps to situation S (a run-time error when there is none).
diag_mod(main,
  [
    [ id ==> is,
      type ==> speech,
      arcs ==> [
        hello : [say(hi), inc(visits, _)] => ask1,
        bye : [say(bye)] => fs,
        % a next situation from the input: `go(nowhere)` is a run-time error
        go(S) : [] => S
      ]
    ],
    [ id ==> ask1,
      type ==> recursive,
      embedded_dm ==> ask(color),
      arcs ==> [
        got(C) : [set(color, C)] => is,
        failed : [] => is
      ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ color ==> none,
    visits ==> 0
  ]
).
