% main: Golem greets the guest, asks for a drink (the DM ask_drink) and
% brings it. The drink chosen comes back as the id of the final situation
% ask_drink ends in, and down the pipe.
diag_mod(main,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : say('Hello, I am Golem.') => order
      ]
    ],
    [ id ==> order,
      type ==> recursive,
      embedded_dm ==> ask_drink,
      arcs ==> [
        chosen(D) : [say(msg_format(['I will bring you the', D], _)), inc(served, _)] => fs,
        gave_up : say('Maybe later, then.') => fs
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  []
).
