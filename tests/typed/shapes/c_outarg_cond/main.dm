% Shape (c): the callee's out_arg is a computed expression (a conditional:
% the limit back when it is positive, else 1); the limit the recursive
% situation's in_arg; the count a local of the caller (`inc`).
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask,
      type ==> recursive,
      in_arg ==> Lim,
      embedded_dm ==> mirror,
      arcs ==> [ back : [inc(count, C)] => (C < Lim -> ask ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  [ count ==> 0 ]
).

diag_mod(mirror,
  [ [ id ==> take, type ==> neutral, in_arg ==> X,
      out_arg ==> (X > 0 -> X ; otherwise -> 1),
      arcs ==> [ empty : empty => back ] ],
    [ id ==> back, type ==> final ]
  ],
  []
).
