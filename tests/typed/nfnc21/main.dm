% Helper nfnc21 (issue 37): plain functions called by native code on its
% values: a next situation (`walk/2`, `count/2`), a condition whose
% declared variable the next situation names (`find/2`), an out_arg
% (`pump/1`, and `pump_w/1`, `pump_h/1` whose functions are not plain).
diag_mod(walk(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(Places) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> walk([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => apply(step(_, _, _), [P, Ps, Target]) ] ],
    [ id ==> found(_, _), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).

diag_mod(find(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> try([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(same(X, _), [P, Target]) == yes -> got(P, X) ; otherwise -> try(Ps)) ] ],
    [ id ==> got(_, _), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(count(N, K),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(score(_, _), [N, K]) ] ],
    [ id ==> big, type ==> final ],
    [ id ==> even(_), type ==> final ],
    [ id ==> odd(_), type ==> final ]
  ],
  []
).

diag_mod(pump(Start),
  [ [ id ==> s0, type ==> neutral, out_arg ==> Start, arcs ==> [ empty : empty => a1 ] ],
    [ id ==> a1, type ==> recursive, embedded_dm ==> grower, arcs ==> [ added : empty => a2 ] ],
    [ id ==> a2, type ==> recursive, embedded_dm ==> grower, arcs ==> [ added : empty => a3 ] ],
    [ id ==> a3, type ==> recursive, embedded_dm ==> grower, arcs ==> [ added : empty => got ] ],
    [ id ==> got, type ==> neutral, in_arg ==> V, arcs ==> [ empty : empty => fin(V) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(grower,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(grow(_), [X]),
      arcs ==> [ empty : empty => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).

diag_mod(pump_w(Start),
  [ [ id ==> s0, type ==> neutral, out_arg ==> Start, arcs ==> [ empty : empty => a1 ] ],
    [ id ==> a1, type ==> recursive, embedded_dm ==> wrapper, arcs ==> [ added : empty => a2 ] ],
    [ id ==> a2, type ==> recursive, embedded_dm ==> wrapper, arcs ==> [ added : empty => got ] ],
    [ id ==> got, type ==> neutral, in_arg ==> V, arcs ==> [ empty : empty => fin(V) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(wrapper,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(wrap(_), [X]),
      arcs ==> [ empty : empty => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).

diag_mod(pump_h(Start),
  [ [ id ==> s0, type ==> neutral, out_arg ==> Start, arcs ==> [ empty : empty => a1 ] ],
    [ id ==> a1, type ==> recursive, embedded_dm ==> holer, arcs ==> [ added : empty => a2 ] ],
    [ id ==> a2, type ==> recursive, embedded_dm ==> holer, arcs ==> [ added : empty => got ] ],
    [ id ==> got, type ==> neutral, in_arg ==> V, arcs ==> [ empty : empty => fin(V) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

diag_mod(holer,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> apply(hole(_), [X]),
      arcs ==> [ empty : empty => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).
