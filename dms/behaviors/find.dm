% find(Object, Shelves, Shelf, Seen, Status): looks for Object on Shelves,
% in the order given: goes to each, looks, and stops at the first shelf
% where it sees Object (Shelf). Seen is everything it saw on the way, the
% latest first, as Shelf-Objects pairs, so that the caller can record
% where other objects are. Where Object is not, the robot says so.
%
% Status: ok, or not_found (no shelf held it; Shelf is `none`).
% Final situations: found(Shelf, Seen), error(not_found, Seen).
diag_mod(find(Object, Shelves, _Shelf, _Seen, _Status),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => look(Shelves, []) ]
    ],
    [ id ==> look([], Seen),
      type ==> neutral,
      arcs ==> [
        empty : say(['I could not find', the, Object]) => error(not_found, Seen)
      ]
    ],
    [ id ==> look([S|Ss], Seen),
      type ==> recursive,
      embedded_dm ==> move(S, _),
      arcs ==> [
        success : empty => at(S, Ss, Seen),
        % a shelf it cannot reach: say so and try the next one
        error(_) : say(['I cannot', reach, apply(name_of(_), [S])]) => look(Ss, Seen)
      ]
    ],
    [ id ==> at(S, Ss, Seen),
      type ==> recursive,
      embedded_dm ==> see(Os, _),
      arcs ==> [
        success(Os) : empty =>
          ( member(Object, Os) -> found(S, [S-Os|Seen])
          ; otherwise -> missing(S, Ss, [S-Os|Seen]) )
      ]
    ],
    [ id ==> missing(S, Ss, Seen),
      type ==> neutral,
      arcs ==> [
        empty : say(['The', Object, apply(is_are(_), [Object]), 'not in',
                     apply(name_of(_), [S])]) => look(Ss, Seen)
      ]
    ],
    [ id ==> found(S, Seen),
      type ==> final,
      diag_mod ==> find(Object, Shelves, S, Seen, ok)
    ],
    [ id ==> error(E, Seen),
      type ==> final,
      diag_mod ==> find(Object, Shelves, none, Seen, E)
    ]
  ],
  []
).
