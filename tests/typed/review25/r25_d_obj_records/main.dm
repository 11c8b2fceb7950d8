% Helper review25 (issue 37, shape d): a walk of records
% `obj(Name, Place, Weight)` taken apart in the compound id, for the first
% object in the kitchen heavier than a limit (a guard on an atom, then on an
% integer); the rounds left are a local read by `get` and written by `set`
% in the caller's exit arcs.
diag_mod(haul(Rounds, Objs, Max),
  [ [ id ==> start,
      type ==> neutral,
      arcs ==> [ empty : set(left, Rounds) => trip ]
    ],
    [ id ==> trip,
      type ==> recursive,
      embedded_dm ==> weigh(Objs, Max),
      arcs ==> [ lift(_N) : [get(left, L), L1 is L - 1, set(left, L1)] => (L1 =< 0 -> rest ; otherwise -> trip),
                 nothing : [get(left, L), L1 is L - 1, set(left, L1)] => (L1 =< 0 -> rest ; otherwise -> trip) ]
    ],
    [ id ==> rest, type ==> final ]
  ],
  [ left ==> 0 ]
).

diag_mod(weigh(Objs, Max),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => look(Objs) ]
    ],
    [ id ==> look([]),
      type ==> neutral,
      arcs ==> [ empty : empty => nothing ]
    ],
    [ id ==> look([obj(N, P, W)|Os]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (P \== kitchen -> look(Os)
                   ; otherwise -> (W > Max -> lift(N) ; otherwise -> look(Os))) ]
    ],
    [ id ==> lift(_), type ==> final ],
    [ id ==> nothing, type ==> final ]
  ],
  []
).
