% Shape (c): the limit in a local (`set(limit, Max)` once, read by
% `get(limit, _)` inside the condition); the count in the pipe, incremented
% two levels down (`hop` passes it through a neutral situation with
% `out_arg ==> X`, then calls `bump`, which hands back `Y is X + 1`); the
% caller reads it on a neutral situation.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0,
      arcs ==> [ empty : [set(limit, Max)] => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> hop,
      arcs ==> [ done : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> C,
      arcs ==> [ empty : empty => (C < get(limit, _) -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ limit ==> 0 ]
).

diag_mod(hop,
  [ [ id ==> pass, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => down ] ],
    [ id ==> down, type ==> recursive, embedded_dm ==> bump,
      arcs ==> [ bumped : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(bump,
  [ [ id ==> add, type ==> neutral, in_arg ==> X, out_arg ==> Y,
      arcs ==> [ empty : [Y is X + 1] => bumped ] ],
    [ id ==> bumped, type ==> final ]
  ],
  []
).
