% review: turns 28-30 (Appendix B.3, first part). For each delivered
% object, where it was taken is compared with where it should be (its
% preferred location once the last-seen one is set aside); when they
% differ the robot asks whether to make the place where it was found the
% preferred one, and updates the KB if the user agrees.
diag_mod(review,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => each(get(taken, _)) ]
    ],
    [ id ==> each([]),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> each([O-Shelf|Ps]),
      type ==> neutral,
      arcs ==> [
        empty : assign(P, apply(preferred_place(_, _),
                                [apply(object_property_list(_, _), [O, loc]), Shelf]))
                => check(O, Shelf, P, Ps)
      ]
    ],
    [ id ==> check(_, Shelf, Shelf, Ps),
      type ==> neutral,
      arcs ==> [ empty : empty => each(Ps) ]
    ],
    [ id ==> check(O, Shelf, P, Ps),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['I found the', O, 'on', apply(name_of(_), [Shelf]),
                           ', but it should be on', apply(name_of(_), [P]),
                           '; do you want me to change the preferred location of', O,
                           'to', apply(name_of(_), [Shelf]), '?']]),
                          yes_no, get(vocab, _), _, _),
      arcs ==> [
        success(yes) : [ apply(add_object_property_preference(_, _, _),
                               [O, ('-'=>>loc=>Shelf), 1]),
                         say('Ok. I updated my KB with your new preference.') ] => each(Ps),
        success(_) : say(['Ok. The', O, 'will stay on', apply(name_of(_), [P])]) => each(Ps),
        error(_) : empty => each(Ps)
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
