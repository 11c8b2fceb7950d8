% Helper npipe25 (issue 37): a native in_arg that reads the whole pipe
% (`in_arg ==> L`) where a native out_arg left it held (`Cx::pipe_as`):
% a list handed to a callee and back at each call, of atoms, of compounds,
% with unbound cells or an improper tail (not held: the term path), read
% as a list and as a `ground` value; a compound held as its arguments
% (`out_arg ==> pair(N, L)`) read whole; an int and an atom; the pipe read
% and rewritten by the machine between (a recursive situation whose
% in_arg is a pattern, term code) before a native in_arg reads it.

% The list handed to `turn` by out_arg and read back by in_arg; `Mode`
% says what `turn` hands back.
diag_mod(loop(Rounds, Items, Mode),
  [ [ id ==> load, type ==> neutral, out_arg ==> Items,
      arcs ==> [ empty : empty => call ] ],
    [ id ==> call, type ==> recursive, embedded_dm ==> turn(Mode),
      arcs ==> [ turned : empty => check ] ],
    [ id ==> check, type ==> neutral, in_arg ==> Got, out_arg ==> Got,
      arcs ==> [ empty : [inc(n, N)] => (N >= Rounds -> done(Got) ; otherwise -> call) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  [ n ==> 0 ]
).

% `rev`: the list reversed (held whole); `same`: the pipe unchanged;
% `wrap`: `box(L)`, a compound of the list; `len`: its length, an int.
diag_mod(turn(Mode),
  [ [ id ==> begin, type ==> neutral, in_arg ==> L,
      arcs ==> [ empty : empty => go(Mode, L) ] ],
    [ id ==> go(rev, L), type ==> neutral,
      arcs ==> [ empty : empty => walk(L, []) ] ],
    [ id ==> go(wrap, L), type ==> neutral,
      arcs ==> [ empty : empty => boxed(L) ] ],
    [ id ==> go(len, L), type ==> neutral,
      arcs ==> [ empty : empty => count(L, 0) ] ],
    [ id ==> go(same, _), type ==> neutral,
      arcs ==> [ empty : empty => turned ] ],
    [ id ==> walk([], Acc), type ==> neutral, out_arg ==> Acc,
      arcs ==> [ empty : empty => turned ] ],
    [ id ==> walk([P|Ps], Acc), type ==> neutral,
      arcs ==> [ empty : empty => walk(Ps, [P|Acc]) ] ],
    [ id ==> boxed(B), type ==> neutral, out_arg ==> box(B),
      arcs ==> [ empty : empty => turned ] ],
    [ id ==> count([], K), type ==> neutral, out_arg ==> K,
      arcs ==> [ empty : empty => turned ] ],
    [ id ==> count([_|Ps], K), type ==> neutral,
      arcs ==> [ empty : [K1 is K + 1] => count(Ps, K1) ] ],
    [ id ==> turned, type ==> final ]
  ],
  []
).

% A compound of native values held as its arguments (`hold_pipe`), read
% whole by the callee's in_arg and handed back; the caller takes it apart.
diag_mod(pairs(Rounds, Items),
  [ [ id ==> load, type ==> neutral, out_arg ==> pair(0, Items),
      arcs ==> [ empty : empty => call ] ],
    [ id ==> call, type ==> recursive, embedded_dm ==> echo,
      arcs ==> [ echoed : empty => check ] ],
    [ id ==> check, type ==> neutral, in_arg ==> pair(N, L), out_arg ==> pair(N1, L),
      arcs ==> [ empty : [N1 is N + 1] => (N1 >= Rounds -> done(N1, L) ; otherwise -> call) ] ],
    [ id ==> done(_, _), type ==> final ]
  ],
  []
).

diag_mod(echo,
  [ [ id ==> step, type ==> neutral, in_arg ==> P, out_arg ==> P,
      arcs ==> [ empty : empty => echoed ] ],
    [ id ==> echoed, type ==> final ]
  ],
  []
).

% The machine reads the list held by `turn(rev)`'s out_arg (a recursive
% situation with an in_arg pattern, term code) and rewrites the pipe (its
% out_arg, `[Fill, H|T]`: with `Fill` unbound, not ground, so the native
% in_arg of `check` hands over to the machine) before `check` reads it.
diag_mod(between(Rounds, Items, Fill),
  [ [ id ==> load, type ==> neutral, out_arg ==> Items,
      arcs ==> [ empty : empty => call ] ],
    [ id ==> call, type ==> recursive, embedded_dm ==> turn(rev),
      arcs ==> [ turned : empty => peek ] ],
    [ id ==> peek, type ==> recursive, in_arg ==> [H|T], out_arg ==> [Fill, H|T],
      embedded_dm ==> turn(rev),
      arcs ==> [ turned : empty => check ] ],
    [ id ==> check, type ==> neutral, in_arg ==> Got, out_arg ==> Got,
      arcs ==> [ empty : [inc(n, N)] => (N >= Rounds -> done(Got) ; otherwise -> call) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  [ n ==> 0 ]
).
