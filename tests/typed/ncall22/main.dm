% Helper ncall22 (issue 37): calls whose arguments are evaluated, pushed
% natively by DMs without locals (the call evaluated once, read-only, the
% waiting variant holding it): `get` of a global the callee changes,
% `apply` of a function with a side effect (counted once), arithmetic,
% an output argument, values that do not convert (not ground: the
% machine's call with the evaluated term), an evaluation that fails. (The
% MIR types an evaluated argument `ground`, so the callees' parameters are
% `ground`.) The callees hand over while
% they run (`hand/1` is not plain), so the waiting caller becomes the
% machine's. Each task must give what the interpreter gives
% (tests/tests/suite/typed/ncall22.rs), with and without history.

% `get` of a global the callee sets before it hands over (`up/1` adds
% one: an int, a value that does not add, one that is not ground).
diag_mod(tint(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> up(get(g, _)),
      arcs ==> [ got(V, C) : empty => stop(V, C, get(g, _)) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% `get` of a global, a list the callee walks.
diag_mod(tlist(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> len(get(g, _), x),
      arcs ==> [ n(N, C) : empty => stop(N, C) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

% `get` of a global, and an output argument the exit arc reads.
diag_mod(tatom(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> yn(get(g, _), W),
      arcs ==> [ said(C) : empty => stop(W, C) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

% `apply` of a function with a side effect (`same/1` counts its calls and
% gives its argument), the callee adding one to its value.
diag_mod(side(S),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> up(apply(same(_), [S])),
      arcs ==> [ got(V, C) : empty => after(V, C) ] ],
    [ id ==> after(V, C), type ==> neutral,
      arcs ==> [ empty : empty => stop(V, C, apply(count(_), [x])) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% `apply` with a side effect whose value the callee takes whatever it is
% on terms, but not natively when it is not ground: one call either way.
diag_mod(loose(S),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> keep(apply(tally(_), [S])),
      arcs ==> [ kept(V, C) : empty => after(V, C) ] ],
    [ id ==> after(V, C), type ==> neutral,
      arcs ==> [ empty : empty => stop(V, C, apply(count(_), [x])) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% An evaluation that fails (no such function, arithmetic on an atom).
diag_mod(fails(K),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> up(_ is K * 3),
      arcs ==> [ got(V, C) : empty => stop(V, C) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

% Two held calls in a row, the second reading what the first's exit set.
diag_mod(chain(G),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [say(apply(reset(_), [x])), set(g, G)] => one ] ],
    [ id ==> one, type ==> recursive, embedded_dm ==> up(get(g, _)),
      arcs ==> [ got(V, _) : set(g, V) => two ] ],
    [ id ==> two, type ==> recursive, embedded_dm ==> up(get(g, _)),
      arcs ==> [ got(W, C) : empty => stop(W, C, get(g, _)) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

% The callees.

% Sets `g`, hands over, then adds one to its parameter.
diag_mod(up(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : set(g, up) => apply(hand(_), [X]) ] ],
    [ id ==> at(C), type ==> neutral,
      arcs ==> [ empty : empty => got(_ is X + 1, C) ] ],
    [ id ==> got(_, _), type ==> final ]
  ],
  []
).

% Hands over, then counts the elements of its list.
diag_mod(len(L, _),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(hand(_), [L]) ] ],
    [ id ==> at(C), type ==> neutral, arcs ==> [ empty : empty => walk(L, 0, C) ] ],
    [ id ==> walk([], N, C), type ==> neutral, arcs ==> [ empty : empty => n(N, C) ] ],
    [ id ==> walk([_|T], N, C), type ==> neutral,
      arcs ==> [ empty : empty => walk(T, _ is N + 1, C) ] ],
    [ id ==> n(_, _), type ==> final ]
  ],
  []
).

% Hands over, then says whether its atom is `yes` (its output `W`).
diag_mod(yn(A, W),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(hand(_), [A]) ] ],
    [ id ==> at(C), type ==> neutral,
      arcs ==> [ empty : empty => ( A == yes -> said(C) ; otherwise -> other(C) ) ] ],
    [ id ==> other(C), type ==> neutral, arcs ==> [ empty : empty => said(C) ] ],
    [ id ==> said(_), type ==> final, diag_mod ==> yn(A, A) ]
  ],
  []
).

% Hands over, then gives its parameter back.
diag_mod(keep(X),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(hand(_), [X]) ] ],
    [ id ==> at(C), type ==> neutral, arcs ==> [ empty : empty => kept(X, C) ] ],
    [ id ==> kept(_, _), type ==> final ]
  ],
  []
).
