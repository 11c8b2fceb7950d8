% place(Object, Shelf, Status): the robot takes Object, which it holds, to
% Shelf and puts it there.
%
% Status: ok, not_holding (no hand holds Object), navigation_error, or
% on_floor (it was put down where there is no shelf and fell).
% Final situations: success, error(Status).
diag_mod(place(Object, Shelf, _Status),
  [
    [ id ==> is,
      type ==> hands,
      arcs ==> [
        hands(_, _) : empty => error(not_holding),
        hands(_, Object) : empty => go(right),
        hands(Object, _) : empty => go(left)
      ]
    ],
    [ id ==> go(Hand),
      type ==> recursive,
      embedded_dm ==> move(Shelf, _),
      arcs ==> [
        success : place(Hand, Result) => placed(Result),
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> placed(ok),
      type ==> neutral,
      arcs ==> [ empty : empty => success ]
    ],
    [ id ==> placed(Error),
      type ==> neutral,
      arcs ==> [ empty : empty => error(Error) ]
    ],
    [ id ==> success,
      type ==> final,
      diag_mod ==> place(Object, Shelf, ok)
    ],
    [ id ==> error(E),
      type ==> final,
      diag_mod ==> place(Object, Shelf, E)
    ]
  ],
  []
).
