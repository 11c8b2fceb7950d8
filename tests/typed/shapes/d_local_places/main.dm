% Shape (d): the places a local variable of the caller (its default), read
% with `get` in the call; the target the caller's parameter; the searching
% DM takes only the list and the target; rounds in a local (`inc`).
diag_mod(tour(Rounds, Target),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> search(get(places, _), Target),
      arcs ==> [ found(P) : [inc(n, N)] => (N >= Rounds -> stop ; otherwise -> round),
                 not_found : [inc(n, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ n ==> 0,
    places ==> [hall, kitchen, pantry, study, garage, porch, attic, cellar] ]
).

diag_mod(search(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
