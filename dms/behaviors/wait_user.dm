% wait_user(Place, Seconds, Status): the robot goes to Place and waits
% there for the user, Seconds at most.
%
% Status: ok (the user is here), navigation_error, or no_user (nobody came).
% Final situations: success, error(Status).
diag_mod(wait_user(Place, Seconds, _Status),
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> move(Place, _),
      arcs ==> [
        success : empty => waiting,
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> waiting,
      type ==> presence(Seconds),
      arcs ==> [
        nobody : empty => error(no_user),
        user : empty => success
      ]
    ],
    [ id ==> success,
      type ==> final,
      diag_mod ==> wait_user(Place, Seconds, ok)
    ],
    [ id ==> error(E),
      type ==> final,
      diag_mod ==> wait_user(Place, Seconds, E)
    ]
  ],
  []
).
