% find_user(Places, Place, Status): the robot looks for the user at
% Places, in the order given (the most likely first), and stops where it
% finds them (Place).
%
% Status: ok, or no_user (not at any of them; Place is `none`).
% Final situations: found(Place), error(no_user).
diag_mod(find_user(Places, _Place, _Status),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => try(Places) ]
    ],
    [ id ==> try([]),
      type ==> neutral,
      arcs ==> [ empty : say('I cannot find you.') => error(no_user) ]
    ],
    [ id ==> try([P|Ps]),
      type ==> recursive,
      embedded_dm ==> move(P, _),
      arcs ==> [
        success : empty => look(P, Ps),
        error(_) : empty => try(Ps)
      ]
    ],
    [ id ==> look(P, Ps),
      type ==> presence(0),
      arcs ==> [
        nobody : empty => try(Ps),
        user : empty => found(P)
      ]
    ],
    [ id ==> found(P),
      type ==> final,
      diag_mod ==> find_user(Places, P, ok)
    ],
    [ id ==> error(E),
      type ==> final,
      diag_mod ==> find_user(Places, none, E)
    ]
  ],
  []
).
