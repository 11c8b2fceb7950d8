% An out_arg the evaluator computes in a DM with locals (`n`, held in
% native code's frame): it reads the local set in the same arc (`s`),
% `inc`s it (`t`: the next situation's value read it before), and calls
% `F`, the DM's parameter, on it (`u`: `twice(_)`, or `nofun(_)`, which
% fails). The local's value after the out_arg, read by `u`'s action,
% ends in the final's id.
diag_mod(main(K, F),
  [ [ id ==> s, type ==> neutral,
      out_arg ==> apply(when(_, _, _), [get(n, _) > 2, big, small]),
      arcs ==> [ empty : [set(n, K)] => t(K) ] ],
    [ id ==> t(X), type ==> neutral, in_arg ==> A,
      out_arg ==> apply(when(_, _, _), [inc(n, _) > 3, A, little]),
      arcs ==> [ empty : empty => u(X, A) ] ],
    [ id ==> u(X, A), type ==> neutral, in_arg ==> B,
      out_arg ==> apply(F, [get(n, _)]),
      arcs ==> [ empty : [get(n, M)] => fin(X, A, B, M) ] ],
    [ id ==> fin(_, _, _, _), type ==> final ]
  ],
  [ n ==> 0 ]
).
