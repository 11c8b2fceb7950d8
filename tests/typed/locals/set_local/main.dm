% `set(l, ..)` of locals in arcs: constants (`set(n, 0)`, `set(k, 2)`) and
% a value the expectation binds (`set(m, W)`, `W` the callee's parameter),
% in neutral arcs and callers' exit arcs; `m` is then counted (`inc`), so a
% value that is no number is the machine's error there. `n` counts the
% rounds, so that every run ends.
diag_mod(main(Max, V),
  [ [ id ==> s, type ==> neutral, arcs ==> [ empty : [set(n, 0), set(m, 1)] => loop ] ],
    [ id ==> loop, type ==> neutral,
      arcs ==> [ empty : [inc(n, N)] => (N >= 3 -> hop ; otherwise -> loop) ] ],
    [ id ==> hop, type ==> recursive, embedded_dm ==> echo(V),
      arcs ==> [ back(W) : [set(m, W), set(k, 2)] => add ] ],
    [ id ==> add, type ==> neutral,
      arcs ==> [ empty : [inc(m, M)] => (M >= Max -> over ; otherwise -> again) ] ],
    [ id ==> again, type ==> recursive, embedded_dm ==> echo(V),
      arcs ==> [ back(W) : [inc(n, N), set(m, W), get(k, K), K] => (N >= 6 -> over ; otherwise -> add) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ n ==> 0, m ==> 0, k ==> 0 ]
).

diag_mod(echo(X),
  [ [ id ==> e, type ==> neutral, arcs ==> [ empty : empty => back(X) ] ],
    [ id ==> back(X), type ==> final ]
  ],
  []
).
