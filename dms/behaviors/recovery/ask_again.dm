% ask_again(Question): recovery protocol of `ask`. The answer to Question
% was not understood: say so and ask it again.
diag_mod(ask_again(Question),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ say('Sorry, I did not understand you.'), say(Question) ] => asked
      ]
    ],
    [ id ==> asked,
      type ==> final
    ]
  ],
  []
).
