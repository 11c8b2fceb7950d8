% `when/3`'s own variables bound where it is called: the runtime's `when/3`
% is given a bound variable's value as written (`eval::apply`), not the
% condition's. `C` is a DM parameter (the caller's value decides); `W` is
% named again after the call (`apply` binds it, `say(W)` says it); `K` is the
% in_arg. Only a `when` whose three variables the situation names nowhere
% else is the conditional it looks like.
diag_mod(main(C, X),
  [ [ id ==> start, type ==> neutral,
      out_arg ==> apply(when(C, _, _), [X == a, yes, no]),
      arcs ==> [ empty : [say(apply(when(W, _, _), [X == a, yes, no])), say(W)] => next ] ],
    [ id ==> next, type ==> neutral, in_arg ==> K,
      arcs ==> [ empty : [say(K)] => apply(when(K, _, _), [X == a, fin, other]) ] ],
    [ id ==> fin, type ==> final ],
    [ id ==> other, type ==> final ]
  ],
  []
).
