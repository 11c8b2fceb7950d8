% take(Object, Hand, Status): the robot grasps Object from the shelf in
% front of it with a free hand, the left one first (Hand: left or right).
% A grasp that fails is a common error: the recovery protocol `regrasp`
% says so and tries once more.
%
% Status: ok, hands_full, not_in_view (it cannot see Object here), or
% grasp_failed (the second attempt failed too).
% Final situations: success(Hand), error(Status, Hand).
diag_mod(take(Object, _Hand, _Status),
  [
    % Which hands are free: the robot feels its hands. The last arc whose
    % expectation is met wins, so the most specific comes last.
    [ id ==> is,
      type ==> hands,
      arcs ==> [
        hands(_, _) : empty => error(hands_full, none),
        hands(_, free) : empty => grab(right),
        hands(free, _) : empty => grab(left)
      ]
    ],
    [ id ==> grab(Hand),
      type ==> neutral,
      arcs ==> [
        empty : [ say(['Attempting to grab the', Object, 'with my', Hand, arm]),
                  grasp(Object, Hand, Result) ] => grabbed(Hand, Result, first)
      ]
    ],
    [ id ==> grabbed(Hand, ok, _),
      type ==> neutral,
      arcs ==> [ empty : say(apply(words(_), [['I took the', Object, '.']])) => success(Hand) ]
    ],
    [ id ==> grabbed(Hand, grasp_failed, first),
      type ==> recursive,
      embedded_dm ==> regrasp(Object, Hand, _),
      arcs ==> [ result(Result) : empty => grabbed(Hand, Result, again) ]
    ],
    [ id ==> grabbed(Hand, not_in_view, _),
      type ==> neutral,
      arcs ==> [
        empty : say(['I cannot see the', Object, here]) => error(not_in_view, Hand)
      ]
    ],
    [ id ==> grabbed(Hand, Error, _),
      type ==> neutral,
      arcs ==> [
        empty : say(['I could not take', the, Object]) => error(Error, Hand)
      ]
    ],
    [ id ==> success(Hand),
      type ==> final,
      diag_mod ==> take(Object, Hand, ok)
    ],
    [ id ==> error(E, Hand),
      type ==> final,
      diag_mod ==> take(Object, Hand, E)
    ]
  ],
  []
).
