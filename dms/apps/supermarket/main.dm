% The supermarket assistant: the deliberative-inference scenario of the
% 2021 SitLog paper (Figure 1 and Sections 7-8), written for sitlog-rs.
%
% The robot learns its words and the right shelf of every product from its
% KB, looks at the shelf in front of it (its cognitive obligations hold for
% every observation), greets the customer and offers help, checks the age
% restriction of what is asked for, and serves it: when the world is not as
% it believes, the daily-life inference cycle (serve.dm) diagnoses, decides
% and plans. Every sentence comes from the world, the KB and the dialogue.
diag_mod(main,
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> learn,
      arcs ==> [ done : empty => here(apply(shop_shelf_here, [])) ]
    ],
    [ id ==> here(none),
      type ==> neutral,
      arcs ==> [ empty : empty => greet ]
    ],
    [ id ==> here(Shelf),
      type ==> recursive,
      embedded_dm ==> see(_, _),
      arcs ==> [ success(Objects) : empty => check(Shelf, Objects) ]
    ],
    [ id ==> check(Shelf, Objects),
      type ==> recursive,
      embedded_dm ==> observe(Shelf, Objects, none),
      arcs ==> [
        seen : empty => greet,
        missing : empty => greet
      ]
    ],
    [ id ==> greet,
      type ==> recursive,
      embedded_dm ==> ask('Hello! I am Golem, the assistant of this shop. Can I help you?',
                          request, get(vocab, _), _, _),
      arcs ==> [
        success(order([Item|_])) : empty => product(Item),
        success(_) : say('Ok. Enjoy your shopping!') => closing,
        error(_) : say('Ok. Enjoy your shopping!') => closing
      ]
    ],
    [ id ==> product(object(O)),
      type ==> neutral,
      arcs ==> [ empty : empty => restricted(O) ]
    ],
    [ id ==> product(class(C)),
      type ==> neutral,
      arcs ==> [
        empty : empty => restricted(apply(first_of(_), [apply(objects_of_a_class(_), [C])]))
      ]
    ],
    [ id ==> product(unknown(W)),
      type ==> neutral,
      arcs ==> [ empty : say(['Sorry, we do not', sell, W]) => closing ]
    ],
    [ id ==> restricted(none),
      type ==> neutral,
      arcs ==> [ empty : say('Sorry, we do not have that.') => closing ]
    ],
    % The age restriction of the KB (class beer: min_age=>18).
    [ id ==> restricted(O),
      type ==> neutral,
      arcs ==> [
        empty : assign(Age, apply(object_property_value(_, _), [O, min_age])) => age(O, Age)
      ]
    ],
    [ id ==> age(O, unknown),
      type ==> neutral,
      arcs ==> [ empty : empty => serve(O) ]
    ],
    [ id ==> age(O, Age),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['The', O, 'is only for people over', Age, '. Are you over', Age, '?']]),
                          yes_no, get(vocab, _), _, _),
      arcs ==> [
        success(yes) : say(['Ok. I will bring you', the, O]) => serve(O),
        success(no) : say(['Sorry, I cannot bring you', the, O]) => closing,
        error(_) : say(['Sorry, I cannot bring you', the, O]) => closing
      ]
    ],
    [ id ==> serve(O),
      type ==> recursive,
      embedded_dm ==> serve(O),
      arcs ==> [
        done : empty => closing,
        none : empty => closing
      ]
    ],
    [ id ==> closing,
      type ==> neutral,
      arcs ==> [
        empty : [ say('Thank you for shopping with us. Goodbye!'),
                  assign(P, apply(pending_objects(_), [get(pending, _)])),
                  ( P == [] -> empty
                  ; otherwise -> message(apply(name_of(_), [manager]), ['Still to put', 'back:', apply(things(_), [P])]) ) ]
                => fs
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  []
).
