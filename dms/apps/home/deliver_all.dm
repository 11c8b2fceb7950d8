% deliver_all: the robot looks for the user where the KB says they are
% most likely to be (object_property_list(user, found_in, L): the chained
% conditional defaults, Appendix B.2) and hands over what it holds, the
% right hand first. The place is kept in the global `user_place`.
% Final situations: done, error(no_user).
diag_mod(deliver_all,
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> find_user(apply(unique(_),
                                      [apply(object_property_list(_, _), [user, found_in])]),
                                _, _),
      arcs ==> [
        found(Place) : set(user_place, Place) => give(right),
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> give(Hand),
      type ==> recursive,
      embedded_dm ==> deliver(Hand, _, _),
      arcs ==> [
        success(_) : empty => after(Hand),
        error(empty_hand, _) : empty => after(Hand),
        error(E, _) : empty => error(E)
      ]
    ],
    [ id ==> after(right),
      type ==> neutral,
      arcs ==> [ empty : empty => give(left) ]
    ],
    [ id ==> after(left),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
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
