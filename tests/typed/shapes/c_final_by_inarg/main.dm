% Shape (c): the count travels in the pipe (the recursive situation's
% out_arg `J`, computed in its exit arc); the callee's final is chosen by
% a condition on its in_arg (`N > 10 -> big ; small`) and the caller
% matches both. The limit is the caller's parameter, the count also in
% its id.
diag_mod(relay(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I),
      type ==> recursive,
      embedded_dm ==> size,
      out_arg ==> J,
      arcs ==> [ big : [J is I + 1] => (J < Max -> ask(J) ; otherwise -> over),
                 small : [J is I + 1] => (J < Max -> ask(J) ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(size,
  [ [ id ==> look, type ==> neutral, in_arg ==> N,
      arcs ==> [ empty : empty => (N > 10 -> big ; otherwise -> small) ] ],
    [ id ==> big, type ==> final ],
    [ id ==> small, type ==> final ]
  ],
  []
).
