% preferences: turns 1-10. For each class of comestibles the robot asks
% which member the user likes best, two at a time (the winner stays), says
% what it thinks of the choice (the KB knows which drinks are healthy), and
% stores the answer as preferences of the class ('-'=>>serve=>X: weight 1
% for the favourite, 2 for the others, Appendix B.1). Then it asks whether
% there is more.
diag_mod(preferences,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : say(apply(words(_), [['Hi,', apply(name_of(_), [user]), '.']])) =>
          classes(apply(sons_of_class(_), [comestible]), first)
      ]
    ],
    [ id ==> classes([], _),
      type ==> neutral,
      arcs ==> [ empty : empty => more ]
    ],
    [ id ==> classes([C|Cs], Turn),
      type ==> neutral,
      arcs ==> [ empty : empty => compare(C, apply(class_extension(_), [C]), [], Cs, Turn) ]
    ],
    % nothing (more) to compare: store the favourite and the others
    [ id ==> compare(_, [], _, Cs, Turn),
      type ==> neutral,
      arcs ==> [ empty : empty => classes(Cs, Turn) ]
    ],
    [ id ==> compare(C, [Best], Others, Cs, Turn),
      type ==> recursive,
      embedded_dm ==> prefer(C, Best, Others),
      arcs ==> [ done : empty => classes(Cs, Turn) ]
    ],
    [ id ==> compare(C, [A, B|Rest], Others, Cs, Turn),
      type ==> recursive,
      embedded_dm ==> ask(( Turn == first -> apply(words(_), [['Please tell me what do you like best:', A, or, B, '?']])
                          ; otherwise -> apply(words(_), [['What do you like best:', A, or, B, '?']]) ),
                          choice([A, B]), get(vocab, _), _, _),
      arcs ==> [
        success(W) : [ assign(O, ( W == A -> B ; otherwise -> A )),
                       say(apply(health_remark(_, _, _, _),
                                 [W, O,
                                  apply(object_property_value(_, _), [W, healthy]),
                                  apply(object_property_value(_, _), [O, healthy])])) ]
                     => compare(C, [W|Rest], [O|Others], Cs, next),
        error(_) : say('Never mind.') => classes(Cs, next)
      ]
    ],
    [ id ==> more,
      type ==> recursive,
      embedded_dm ==> ask('Do you have any more preferences?', more, get(vocab, _), _, _),
      arcs ==> [
        success(yes) : empty => which,
        success(_) : empty => thanks,
        error(_) : empty => thanks
      ]
    ],
    [ id ==> which,
      type ==> recursive,
      embedded_dm ==> ask('Which one do you like best?',
                          choice(apply(class_extension(_), [comestible])),
                          get(vocab, _), _, _),
      arcs ==> [
        success(X) : [ apply(add_object_property_preference(_, _, _),
                             [X, ('-'=>>serve=>X), 1]),
                       say('Great! I will recall your choice!') ] => more,
        error(_) : empty => more
      ]
    ],
    [ id ==> thanks,
      type ==> neutral,
      arcs ==> [ empty : say(['Thank', 'you,', apply(name_of(_), [user])]) => done ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
