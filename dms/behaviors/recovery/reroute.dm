% reroute(Place, From, To, Result): recovery protocol of `move`. The way
% From-To was found blocked on the way to Place: say so, and go to Place by
% another route (the robot now knows the block and plans around it).
% Result is what the second navigation gave (ok, blocked(..), no_route, ..).
diag_mod(reroute(Place, From, To, _Result),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ say(['The way from', apply(name_of(_), [From]), 'to',
                       apply(name_of(_), [To]), 'is blocked; I will take another route']),
                  navigate(Place, Result) ] => result(Result)
      ]
    ],
    [ id ==> result(R),
      type ==> final,
      diag_mod ==> reroute(Place, From, To, R)
    ]
  ],
  []
).
