% The order of evaluation of an arithmetic condition (the review of the
% thirteenth session): the machine evaluates the sides left to right (the
% left side's `get(a, _)`, then the right side's `get(b, C)`, `C` bound:
% it compares), then compares them as numbers. Where both fail (`a` is
% still `none`, no number; `b` is not `C`) the error is the right side's
% `get`, met before the comparison.
diag_mod(main(A, B, C),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : [set(b, B)] => (A == yes -> seta ; otherwise -> s) ] ],
    [ id ==> seta, type ==> neutral, arcs ==> [ empty : [set(a, 1)] => s ] ],
    [ id ==> s, type ==> neutral,
      arcs ==> [ empty : empty => (get(a, _) < get(b, C) -> below ; otherwise -> above) ] ],
    [ id ==> below, type ==> final ],
    [ id ==> above, type ==> final ]
  ],
  []
).
