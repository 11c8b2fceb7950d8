% choose(Order, Items): turns 15-19 (Appendix B.1). Each item of the order
% is resolved by the user's preferences: a class (something to drink) by
% the class's preferred member, offered to the user; an object by
% comparing it with the preferred member of its class, and asking the user
% to choose when they differ. Items are the objects to fetch.
diag_mod(choose(Order, _Items),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => each(Order, []) ]
    ],
    [ id ==> each([], Chosen),
      type ==> neutral,
      arcs ==> [ empty : empty => confirm(apply(reversed(_), [Chosen])) ]
    ],
    % "something to drink": the favourite drink
    [ id ==> each([class(C)|Is], Chosen),
      type ==> neutral,
      arcs ==> [
        empty : empty => favourite(C, apply(class_property_value(_, _), [C, serve]), Is, Chosen)
      ]
    ],
    [ id ==> favourite(C, unknown, Is, Chosen),
      type ==> neutral,
      arcs ==> [ empty : empty => pick(C, Is, Chosen) ]
    ],
    [ id ==> favourite(C, P, Is, Chosen),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['Ok. I will bring you', P, ', your favorite', C, '.']]),
                          offer(P, none), get(vocab, _), _, _),
      arcs ==> [
        success(none) : empty => pick(C, Is, Chosen),
        success(X) : empty => each(Is, [X|Chosen]),
        error(_) : empty => each(Is, [P|Chosen])
      ]
    ],
    [ id ==> pick(C, Is, Chosen),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['Which', C, 'would you like?']]),
                          choice(apply(class_extension(_), [C])), get(vocab, _), _, _),
      arcs ==> [
        success(X) : empty => each(Is, [X|Chosen]),
        error(_) : empty => each(Is, Chosen)
      ]
    ],
    % an object: is it the favourite of its class?
    [ id ==> each([object(O)|Is], Chosen),
      type ==> neutral,
      arcs ==> [
        empty : assign(P, apply(class_property_value(_, _),
                                [apply(class_of_an_object(_), [O]), serve]))
                => ( member(P, [O, unknown]) -> each(Is, [O|Chosen])
                   ; otherwise -> better(O, P, Is, Chosen) )
      ]
    ],
    [ id ==> better(O, P, Is, Chosen),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['But you like', P, 'better than', O, '! Shall I bring you the', O, '?']]),
                          offer(O, P), get(vocab, _), _, _),
      arcs ==> [
        success(X) : empty => each(Is, [X|Chosen]),
        error(_) : empty => each(Is, [O|Chosen])
      ]
    ],
    [ id ==> each([unknown(W)|Is], Chosen),
      type ==> neutral,
      arcs ==> [
        empty : say(['Sorry, I do not know what', W, is]) => each(Is, Chosen)
      ]
    ],
    [ id ==> confirm([]),
      type ==> neutral,
      arcs ==> [ empty : say('Ok, nothing then.') => done([]) ]
    ],
    [ id ==> confirm(Items),
      type ==> neutral,
      arcs ==> [
        empty : say(['Ok. I will bring', you, apply(things(_), [Items])]) => done(Items)
      ]
    ],
    [ id ==> done(Items),
      type ==> final,
      diag_mod ==> choose(Order, Items)
    ]
  ],
  []
).
