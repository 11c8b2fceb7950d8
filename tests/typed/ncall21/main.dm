% Helper ncall21 (issue 37): calls whose arguments are evaluated
% (`embedded_dm ==> echo(get(n, _))`), the case native code must keep the
% evaluated call for: the callee changes what the call read (a global), or
% the evaluation has a side effect (`apply` of a function that asserts and
% counts), and the frames become the machine's while the callee runs (the
% callee calls a function that is not plain: `hand/1` asserts). Each task
% must give what the interpreter gives (tests/tests/suite/typed/ncall21.rs).

% `get` of a local, twice (the second after an `inc`).
diag_mod(loc(N),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> echo(get(n, _)),
      arcs ==> [ saw(V) : inc(n, _) => again(V) ] ],
    [ id ==> again(V), type ==> recursive, embedded_dm ==> slow(get(n, _)),
      arcs ==> [ saw(W, C) : empty => stop(V, W, C, N) ] ],
    [ id ==> stop(_, _, _, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

% `get` of a global the callee sets before it hands over.
diag_mod(glob(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> change(get(g, _)),
      arcs ==> [ saw(V, C) : empty => stop(V, C, get(g, _)) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% `apply` of a function that asserts a fact and counts its calls, the
% callee handing over while it runs; then the count read again.
diag_mod(twice(S),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> slow(apply(tally(_), [S])),
      arcs ==> [ saw(V, C) : empty => stop(V, C, apply(count(_), [x])) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% Arithmetic in the call (`is`) of the parameter.
diag_mod(arith(K),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> slow(_ is K * 2 + 1),
      arcs ==> [ saw(V, C) : empty => stop(V, C) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

% Bad values: a global left unbound, a global of another type than the
% callee's parameter takes (`add/1` adds one to it).
diag_mod(bad(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> add(get(g, _)),
      arcs ==> [ sum(V) : empty => stop(V) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

% The callees.
diag_mod(echo(X),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => saw(X) ] ],
    [ id ==> saw(_), type ==> final ]
  ],
  []
).

% Hands over (`hand/1` is not plain), then reads its parameter.
diag_mod(slow(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(hand(_), [X]) ] ],
    [ id ==> at(C), type ==> neutral, arcs ==> [ empty : empty => saw(X, C) ] ],
    [ id ==> saw(_, _), type ==> final ]
  ],
  []
).

% Sets the global its caller read, hands over, then reads its parameter.
diag_mod(change(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : set(g, changed) => hand ] ],
    [ id ==> hand, type ==> neutral,
      arcs ==> [ empty : empty => apply(hand(_), [X]) ] ],
    [ id ==> at(C), type ==> neutral, arcs ==> [ empty : empty => saw(X, C) ] ],
    [ id ==> saw(_, _), type ==> final ]
  ],
  []
).

diag_mod(add(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => sum(_ is X + 1) ] ],
    [ id ==> sum(_), type ==> final ]
  ],
  []
).
