% move(Place, Status): the robot goes to Place (a place of the world, or a
% shelf: the place in front of it).
%
% Status: ok, or navigation_error (no route, an unknown place, or a way
% still blocked after the recovery protocol `reroute` tried another route).
% Final situations: success, error(navigation_error).
diag_mod(move(Place, _Status),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : navigate(Place, Result) => moved(Result, first) ]
    ],
    [ id ==> moved(ok, _),
      type ==> neutral,
      arcs ==> [ empty : empty => success ]
    ],
    % A blocked way is a common error: the recovery protocol takes another route.
    [ id ==> moved(blocked(From, To), first),
      type ==> recursive,
      embedded_dm ==> reroute(Place, From, To, _),
      arcs ==> [ result(Result) : empty => moved(Result, again) ]
    ],
    [ id ==> moved(_, _),
      type ==> neutral,
      arcs ==> [ empty : empty => error(navigation_error) ]
    ],
    [ id ==> success,
      type ==> final,
      diag_mod ==> move(Place, ok)
    ],
    [ id ==> error(E),
      type ==> final,
      diag_mod ==> move(Place, E)
    ]
  ],
  []
).
