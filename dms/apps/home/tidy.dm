% tidy: turns 31-39 (Appendix B.3, abduction). Every object the robot saw
% but was not asked for is checked: when where it was seen differs from
% where it should be, it is `misplaced` (stated in the KB), the KB's
% abductive explanation says why, and the robot offers to put it back.
% Then the robot returns to the user and reports.
diag_mod(tidy,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : empty => each(apply(others(_, _),
                                    [apply(reversed(_), [get(seen, _)]),
                                     apply(keys(_), [get(taken, _)])]), [])
      ]
    ],
    [ id ==> each([], Fixed),
      type ==> neutral,
      arcs ==> [ empty : empty => back(apply(reversed(_), [Fixed])) ]
    ],
    [ id ==> each([O-Shelf|Ps], Fixed),
      type ==> neutral,
      arcs ==> [
        empty : assign(P, apply(preferred_place(_, _),
                                [apply(object_property_list(_, _), [O, loc]), Shelf]))
                => check(O, Shelf, P, Ps, Fixed)
      ]
    ],
    [ id ==> check(_, Shelf, Shelf, Ps, Fixed),
      type ==> neutral,
      arcs ==> [ empty : empty => each(Ps, Fixed) ]
    ],
    [ id ==> check(_, _, unknown, Ps, Fixed),
      type ==> neutral,
      arcs ==> [ empty : empty => each(Ps, Fixed) ]
    ],
    [ id ==> check(O, Shelf, P, Ps, Fixed),
      type ==> neutral,
      arcs ==> [
        empty : [ apply(add_object_property(_, _, _), [O, misplaced, yes]),
                  say(['I also noticed that the', O, apply(is_are(_), [O]),
                       'not in its right place']),
                  say(apply(explanation_words(_, _),
                            [O, apply(explanation_of_individual(_), [O])])) ]
                => offer(O, Shelf, P, Ps, Fixed)
      ]
    ],
    [ id ==> offer(O, Shelf, P, Ps, Fixed),
      type ==> recursive,
      embedded_dm ==> ask('Do you want me to take it to its right shelf?', yes_no,
                          get(vocab, _), _, _),
      arcs ==> [
        success(yes) : say(['Ok. I will take', 'it to', apply(name_of(_), [P])])
                       => fetch(O, Shelf, P, Ps, Fixed),
        success(_) : say('Ok, I will leave it there.') => each(Ps, Fixed),
        error(_) : empty => each(Ps, Fixed)
      ]
    ],
    [ id ==> fetch(O, Shelf, P, Ps, Fixed),
      type ==> recursive,
      embedded_dm ==> move(Shelf, _),
      arcs ==> [
        success : empty => grab(O, P, Ps, Fixed),
        error(_) : empty => each(Ps, Fixed)
      ]
    ],
    [ id ==> grab(O, P, Ps, Fixed),
      type ==> recursive,
      embedded_dm ==> take(O, _, _),
      arcs ==> [
        success(_) : empty => put(O, P, Ps, Fixed),
        error(_, _) : empty => each(Ps, Fixed)
      ]
    ],
    [ id ==> put(O, P, Ps, Fixed),
      type ==> recursive,
      embedded_dm ==> place(O, P, _),
      arcs ==> [
        success : [ apply(change_value_object_property(_, _, _), [O, last_seen, P]),
                    apply(rm_object_property(_, _), [O, misplaced]) ]
                  => each(Ps, [O|Fixed]),
        error(_) : say(['I could not put the', O, back]) => each(Ps, Fixed)
      ]
    ],
    % back with the user: what was put back, and the state of the shelves
    [ id ==> back(Fixed),
      type ==> recursive,
      embedded_dm ==> move(get(user_place, _), _),
      arcs ==> [
        success : empty => report(Fixed, Fixed),
        error(_) : empty => report(Fixed, Fixed)
      ]
    ],
    [ id ==> report([O|Os], Fixed),
      type ==> neutral,
      arcs ==> [ empty : say(['I put the', O, 'on its right shelf']) => report(Os, Fixed) ]
    ],
    [ id ==> report([], []),
      type ==> neutral,
      arcs ==> [ empty : say('All the objects I saw are on their right shelves.') => done ]
    ],
    [ id ==> report([], _),
      type ==> neutral,
      arcs ==> [ empty : say('All the objects are placed on their right shelves.') => done ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
