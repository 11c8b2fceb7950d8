% review18 (issue 37, shape (d)): two lists walked in step, a dot product
% kept in the id; ends in `sum(S)`;
% the caller compares the sum with its threshold. `gauge(Rounds, Xs, Ys, Min)`.
% Its generated Rust did not compile on main `0c8eab3` (fixed by `nlock18`) (E0505: `let fk8 = r8`
% moves the first list's tail in the `step([X|Xs1], [Y|Ys1], Acc)` candidate,
% then the fallback reads it), nor does `r18_d_lockstep_any`'s (a catch-all
% `step(_, _, _)` for lists of different lengths): not in `shapes_prof`.
diag_mod(gauge(Rounds, Xs, Ys, Min),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> dot(Xs, Ys),
      arcs ==> [ sum(S) : [inc(n, K)] =>
                   (K >= Rounds -> fs(S) ; otherwise -> (S >= Min -> round ; otherwise -> low(S))),
                 uneven : [inc(n, K)] => (K >= Rounds -> fs(uneven) ; otherwise -> round) ] ],
    [ id ==> low(S), type ==> neutral,
      arcs ==> [ empty : [say(S)] => round ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(dot(Xs, Ys),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => step(Xs, Ys, 0) ] ],
    [ id ==> step([], [], Acc), type ==> neutral,
      arcs ==> [ empty : empty => sum(Acc) ] ],
    [ id ==> step([X|Xs1], [Y|Ys1], Acc), type ==> neutral,
      arcs ==> [ empty : [Acc1 is Acc + X * Y] => step(Xs1, Ys1, Acc1) ] ],
    [ id ==> sum(_), type ==> final ],
    [ id ==> uneven, type ==> final ]
  ],
  []
).
