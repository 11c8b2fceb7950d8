% give(O): the robot goes to the customer and hands O over from the hand
% that holds it. Final situations: done, error(Status).
diag_mod(give(O),
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> move(get(customer_at, _), _),
      arcs ==> [
        success : empty => hand,
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> hand,
      type ==> hands,
      arcs ==> [
        hands(_, _) : empty => error(not_holding),
        hands(_, O) : empty => hand_over(right),
        hands(O, _) : empty => hand_over(left)
      ]
    ],
    [ id ==> hand_over(Hand),
      type ==> recursive,
      embedded_dm ==> deliver(Hand, _, _),
      arcs ==> [
        success(_) : empty => done,
        error(E, _) : empty => error(E)
      ]
    ],
    [ id ==> done,
      type ==> final
    ],
    [ id ==> error(_),
      type ==> final
    ]
  ],
  []
).
