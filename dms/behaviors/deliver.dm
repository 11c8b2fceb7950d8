% deliver(Hand, Object, Status): the robot hands what it holds in Hand to
% the user, who must be where the robot is, saying "Here is the Object".
%
% Status: ok, empty_hand, or no_user. Final situations: success(Object),
% error(Status, Object).
diag_mod(deliver(Hand, _Object, _Status),
  [
    [ id ==> is,
      type ==> hands,
      arcs ==> [ hands(Left, Right) : empty => holding(Hand, Left, Right) ]
    ],
    [ id ==> holding(left, free, _),
      type ==> neutral,
      arcs ==> [ empty : empty => error(empty_hand, none) ]
    ],
    [ id ==> holding(right, _, free),
      type ==> neutral,
      arcs ==> [ empty : empty => error(empty_hand, none) ]
    ],
    [ id ==> holding(left, Object, _),
      type ==> neutral,
      arcs ==> [ empty : empty => give(Object) ]
    ],
    [ id ==> holding(right, _, Object),
      type ==> neutral,
      arcs ==> [ empty : empty => give(Object) ]
    ],
    [ id ==> give(Object),
      type ==> neutral,
      arcs ==> [
        empty : [ say(['Here', apply(is_are(_), [Object]), the, Object]),
                  hand_over(Hand, Result) ] => given(Object, Result)
      ]
    ],
    [ id ==> given(Object, ok),
      type ==> neutral,
      arcs ==> [ empty : empty => success(Object) ]
    ],
    [ id ==> given(Object, Error),
      type ==> neutral,
      arcs ==> [ empty : empty => error(Error, Object) ]
    ],
    [ id ==> success(Object),
      type ==> final,
      diag_mod ==> deliver(Hand, Object, ok)
    ],
    [ id ==> error(E, Object),
      type ==> final,
      diag_mod ==> deliver(Hand, Object, E)
    ]
  ],
  []
).
