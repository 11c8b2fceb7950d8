% welcome(Order): turns 11-14. The robot waits for the user at the
% entrance, welcomes them back from work (back_from_work in the KB), asks
% how the day was (a bad day is `bad_day`, from which the KB's conditional
% default concludes `tired`) and offers its help. Order is what the user
% asked for (a list of object(O) and class(C)), [] for nothing.
% Final situations: ordered(Order), nothing, error(Status).
diag_mod(welcome(_Order),
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> wait_user(entrance, 86400, _),
      arcs ==> [
        success : apply(add_object_property(_, _, _), [user, back_from_work, yes]) => greet,
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> greet,
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['Hi,', apply(name_of(_), [user]), ', how was your day?']]),
                          mood, get(vocab, _), _, _),
      arcs ==> [
        success(bad) : apply(add_object_property(_, _, _), [user, bad_day, yes])
                       => offer('Sorry to hear that;'),
        success(good) : apply(add_object_property(_, _, _), [user, good_day, yes])
                        => offer('I am glad to hear that;'),
        error(_) : empty => offer('Well,')
      ]
    ],
    [ id ==> offer(Opening),
      type ==> recursive,
      embedded_dm ==> ask([Opening, 'do you want me to do something for you?'],
                          request, get(vocab, _), _, _),
      arcs ==> [
        success(order(Items)) :
          apply(add_object_property(_, _, _), [user, asked_comestible, yes])
          => ordered(Items),
        success(_) : say('Ok. I will be around if you need me.') => nothing,
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> ordered(Items),
      type ==> final,
      diag_mod ==> welcome(Items)
    ],
    [ id ==> nothing,
      type ==> final,
      diag_mod ==> welcome([])
    ],
    [ id ==> error(_),
      type ==> final,
      diag_mod ==> welcome([])
    ]
  ],
  []
).
