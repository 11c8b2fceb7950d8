% ask_drink: asks which drink the guest wants, three times at most.
% Ends in chosen(Drink), with Drink as its out_arg, or in gave_up.
diag_mod(ask_drink,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [inc(tries, _), say('What would you like: water or juice?')] => listen
      ]
    ],
    [ id ==> listen,
      type ==> speech,
      arcs ==> [
        % the last arc that matches wins: the catch-all goes first
        Other : say(msg_format(['Sorry, we have no', Other], _)) => retry,
        water : say('Fresh water, good choice.') => chosen(water),
        juice : say('Orange juice it is.') => chosen(juice)
      ]
    ],
    [ id ==> retry,
      type ==> neutral,
      arcs ==> [
        empty : empty => (get(tries, _) < 3 -> is ; otherwise -> gave_up)
      ]
    ],
    [ id ==> chosen(Drink),
      type ==> final,
      out_arg ==> Drink
    ],
    [ id ==> gave_up,
      type ==> final
    ]
  ],
  [ tries ==> 0 ]
).
