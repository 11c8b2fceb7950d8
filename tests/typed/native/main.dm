% Native code (issue 37): DMs whose registers are all native by the MIR's
% types run on Rust values in generated code (`codegen::native`). Their
% parameters are constants here, so inference types them: lists of atoms
% and of ints, an atom, an int. Shapes: a list walk by compound ids
% (`try([P|Ps])`) ending in `found(P)` or `not_found`, which the caller's
% exit arcs match; an int walk with an arithmetic comparison; a pattern
% with a repeated variable and a constant (`pair([X, X|_])`,
% `step([stop|_])`); nested lists.
diag_mod(main,
  [ [ id ==> a1, type ==> recursive, embedded_dm ==> search([x, y, z, w], z),
      arcs ==> [ found(P) : [inc(n, _)] => a2, not_found : empty => a2 ] ],
    [ id ==> a2, type ==> recursive, embedded_dm ==> search([x, y], q),
      arcs ==> [ found(P) : empty => a3, not_found : [inc(n, _)] => a3 ] ],
    [ id ==> a3, type ==> recursive, embedded_dm ==> above([1, 5, 2, 9, 3], 4),
      arcs ==> [ big(N) : empty => a4, none : empty => a4 ] ],
    [ id ==> a4, type ==> recursive, embedded_dm ==> above([], 4),
      arcs ==> [ big(N) : empty => a5, none : empty => a5 ] ],
    [ id ==> a5, type ==> recursive, embedded_dm ==> pairs([a, b, b, c, stop, d]),
      arcs ==> [ done(X) : empty => a6 ] ],
    [ id ==> a6, type ==> recursive, embedded_dm ==> nested([[a, b], [], [c]]),
      arcs ==> [ flat : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(search(Places, Target),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).

diag_mod(above(Ns, Limit),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => next(Ns) ] ],
    [ id ==> next([N|Rest]), type ==> neutral,
      arcs ==> [ empty : empty => (N > Limit -> big(N) ; otherwise -> next(Rest)) ] ],
    [ id ==> next([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> big(N), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

diag_mod(pairs(Items),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => step(Items) ] ],
    [ id ==> step([stop|_]), type ==> neutral, arcs ==> [ empty : empty => done(stop) ] ],
    [ id ==> step([X, X|Rest]), type ==> neutral, arcs ==> [ empty : empty => done(X) ] ],
    [ id ==> step([_|Rest]), type ==> neutral, arcs ==> [ empty : empty => step(Rest) ] ],
    [ id ==> step([]), type ==> neutral, arcs ==> [ empty : empty => done(none) ] ],
    [ id ==> done(X), type ==> final ]
  ],
  []
).

diag_mod(nested(Lists),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => walk(Lists) ] ],
    [ id ==> walk([[]|Ls]), type ==> neutral, arcs ==> [ empty : empty => walk(Ls) ] ],
    [ id ==> walk([[X|Xs]|Ls]), type ==> neutral, arcs ==> [ empty : empty => walk([Xs|Ls]) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => flat ] ],
    [ id ==> flat, type ==> final ]
  ],
  []
).

% Started from the command line: a next value no situation takes (the
% machine's error, located at `try([P|Ps])`).
diag_mod(stray,
  [ [ id ==> s, type ==> recursive, embedded_dm ==> lost([a, b]),
      arcs ==> [ gone : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(lost(L),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => try(L) ] ],
    [ id ==> try([P|Ps]), type ==> neutral, arcs ==> [ empty : empty => try(Ps) ] ],
    [ id ==> gone, type ==> final ]
  ],
  []
).

% Started from the command line: `find`'s parameters are typed `term`, so
% its native code holds ground terms (checked ground and inert at entry),
% matched against compound patterns in the store.
diag_mod(cmd(Items, Target),
  [ [ id ==> c, type ==> recursive, embedded_dm ==> find(Items, Target),
      arcs ==> [ got(X) : empty => fs, none : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(find(Items, Target),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => look(Items) ] ],
    [ id ==> look([]), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> look([item(K, 3)|_]), type ==> neutral, arcs ==> [ empty : empty => got(K) ] ],
    [ id ==> look([item(K, V)|Rest]), type ==> neutral,
      arcs ==> [ empty : empty => (K == Target -> got(V) ; otherwise -> look(Rest)) ] ],
    [ id ==> look([pair(X, X)|Rest]), type ==> neutral, arcs ==> [ empty : empty => got(X) ] ],
    [ id ==> look([_|Rest]), type ==> neutral, arcs ==> [ empty : empty => look(Rest) ] ],
    [ id ==> got(X), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).

% Boundaries inside a visit: an effector's action built from a native
% value; `is`, `set` and `get` through the machine, what they bind
% converted where the next situation reads it.
diag_mod(big(N),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(['square of', N]) => sq(N) ] ],
    [ id ==> sq(M), type ==> neutral,
      arcs ==> [ empty : [X is M * M, set(v, X), get(v, V)] => sq2(X, V) ] ],
    [ id ==> sq2(X, _), type ==> neutral, arcs ==> [ empty : empty => done(X) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  [ v ==> none ]
).

% Native callers (issue 37, `codegen::native::call`): `rounds` is workload
% (d)'s shape with an extra level: a counter loop (`inc` of a local, its
% value compared with the ground parameter `Rounds`) calling `outer`, which
% calls `search` and maps its finals; the exit arcs match the callee's final
% variants natively, the calls push frames on the native stack. `Rounds`
% not an int: the comparison is evaluated on terms (the machine's error).
diag_mod(rounds(Rounds, Places, Target),
  [ [ id ==> round, type ==> recursive, embedded_dm ==> outer(Places, Target, 7),
      arcs ==> [ hit(P, K) : [inc(n, N), P] => (N >= Rounds -> fs ; otherwise -> round),
                 miss(K) : [inc(n, N), inc(m, _)] => (N >= Rounds -> fs ; otherwise -> round) ] ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0, m ==> 10 ]
).

diag_mod(outer(Places, Target, K),
  [ [ id ==> o, type ==> recursive, embedded_dm ==> search(Places, Target),
      arcs ==> [ found(Target) : [inc(c, _)] => hit(Target, K),
                 not_found : empty => miss(K) ] ],
    [ id ==> hit(P, Q), type ==> final ],
    [ id ==> miss(Q), type ==> final ]
  ],
  [ c ==> 0 ]
).

% No exit arc takes `not_found`: the machine's error, at `w`.
diag_mod(want(Places, Target),
  [ [ id ==> w, type ==> recursive, embedded_dm ==> search(Places, Target),
      arcs ==> [ found(P) : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

% The pipe in native code: the limit as the recursive situation's in_arg
% (a ground term: compared with an int on terms when it is not one), the
% callee handing its in_arg back with `out_arg ==> X`, a final's out_arg.
diag_mod(relay(Tag),
  [ [ id ==> call, type ==> recursive, in_arg ==> Limit, embedded_dm ==> echo(Tag),
      arcs ==> [ back(T) : [inc(n, N)] => (N >= Limit -> fs ; otherwise -> call) ] ],
    [ id ==> fs, type ==> final, out_arg ==> [done, Tag] ]
  ],
  [ n ==> 0 ]
).

% `relay` with a callee that performs an action while its caller waits
% (`cry`'s `say`): the native frames become the machine's there, the
% caller waiting as the interpreter's instance would, its in_arg the pipe
% value its visit read (the callee's out_arg changed the pipe since).
diag_mod(shout(Tag),
  [ [ id ==> call, type ==> recursive, in_arg ==> Limit, embedded_dm ==> cry(Tag),
      arcs ==> [ back(T) : [inc(n, N)] => (N >= Limit -> fs ; otherwise -> call) ] ],
    [ id ==> fs, type ==> final, out_arg ==> [done, Tag] ]
  ],
  [ n ==> 0 ]
).

diag_mod(cry(Tag),
  [ [ id ==> is, type ==> neutral, in_arg ==> X, out_arg ==> [X],
      arcs ==> [ empty : say(Tag) => back(Tag) ] ],
    [ id ==> back(T), type ==> final, out_arg ==> 2 ]
  ],
  []
).

% A caller that reads no pipe: `echo` reads it first, natively (a pipe
% the term code evaluates, `1 + 1`, is handed over there).
diag_mod(pass(Tag),
  [ [ id ==> call, type ==> recursive, embedded_dm ==> echo(Tag),
      arcs ==> [ back(T) : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(echo(Tag),
  [ [ id ==> is, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => back(Tag) ] ],
    [ id ==> back(T), type ==> final ]
  ],
  []
).

% An output argument (`_` given, bound by the callee's `diag_mod`): the
% caller's recursive situation has native code that hands the call to the
% machine on terms (the fresh variable made there); the callee runs natively
% and its final, with `diag_mod`, is the machine's; the caller's exit arc
% reads the bound value.
diag_mod(outer_out(K),
  [ [ id ==> c, type ==> recursive, embedded_dm ==> give(K, V),
      arcs ==> [ given : say(V) => got(V) ] ],
    [ id ==> got(V), type ==> final ]
  ],
  []
).

diag_mod(give(K, Out),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => given ] ],
    [ id ==> given, type ==> final, diag_mod ==> give(K, [K, K]) ]
  ],
  []
).

% Boundaries in native code (issue 37, `codegen::native`): an embedded DM
% call the evaluator computes (`twice/1`, a host function the test
% registers, gives `[X, X]`), handed to the machine as evaluated; a
% conditional expression as an action (its condition decided natively or
% on evaluated sides); a conditional next situation whose condition the
% evaluator computes a side of; a next situation the evaluator computes
% whole; compound values and a list of different shapes built natively
% and selected by a pattern; conditions that are Prolog goals (`member`).
diag_mod(evals(X),
  [ [ id ==> c, type ==> recursive, embedded_dm ==> search(apply(twice(_), [X]), X),
      arcs ==> [ found(P) : empty => d(P), not_found : empty => d(none) ] ],
    [ id ==> d(P), type ==> neutral,
      arcs ==> [ empty : (P == none -> say(apply(twice(_), [P])) ; otherwise -> say([P, P]))
                 => (apply(twice(_), [P]) == [a, a] -> e(P) ; otherwise -> got(apply(twice(_), [b]))) ] ],
    [ id ==> e(P), type ==> neutral,
      arcs ==> [ empty : [say(P), (apply(twice(_), [P]) \== [P, P] -> say(no) ; otherwise -> say(yes))]
                 => plan([take(P, 1), deliver(P), P]) ] ],
    [ id ==> plan([take(Q, N)|Rest]), type ==> neutral, arcs ==> [ empty : say(Rest) => fs(Q) ] ],
    [ id ==> plan(_), type ==> neutral,
      arcs ==> [ empty : (member(X, [a, b]) -> say(in) ; otherwise -> say(out))
                 => (member(X, [b, c]) -> fs(X) ; otherwise -> fs(none)) ] ],
    [ id ==> got([A|_]), type ==> neutral, arcs ==> [ empty : say(A) => plan(A) ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  []
).

% Expectations naming a situation variable (`said(W)`, `W` a parameter):
% held natively, a value, so matching cannot bind it; the machine chooses.
diag_mod(hear(W),
  [ [ id ==> l, type ==> speech,
      arcs ==> [ said(W) : say(W) => fs(W), said(X) : empty => fs(X), other : empty => fs(other) ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  []
).

% A local read by `get` inside a next situation (`walk(get(v, _))`, `v`
% typed `ground`: `none` or a list): the machine's `get`, its value
% converted and selected natively.
diag_mod(walkv,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : set(v, [a, b]) => w ] ],
    [ id ==> w, type ==> neutral, arcs ==> [ empty : empty => walk(get(v, _)) ] ],
    [ id ==> walk([X|Xs]), type ==> neutral, arcs ==> [ empty : say(X) => walk(Xs) ] ],
    [ id ==> walk([]), type ==> final ]
  ],
  [ v ==> none ]
).

% The evaluator failing where native code evaluates a next situation (no
% function `nofun/1`): the machine's error, and the failed transition not
% counted, as on the term path.
diag_mod(fails(K),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => (K == 1 -> part ; otherwise -> (K == 2 -> whole ; otherwise -> cond)) ] ],
    [ id ==> part, type ==> neutral, arcs ==> [ empty : empty => got(apply(nofun(_), [K])) ] ],
    [ id ==> whole, type ==> neutral, arcs ==> [ empty : empty => got(apply(nofun(_), [x])) ] ],
    [ id ==> cond, type ==> neutral,
      arcs ==> [ empty : empty => (apply(nofun(_), [K]) == x -> got(x) ; otherwise -> got(y)) ] ],
    [ id ==> got(_), type ==> final ]
  ],
  []
).

% `[H|T]` of ground values built natively (`Val::cons`): a list when `T` is
% one, else an improper list (`[a|b]`), matched again by `[Y|Ys]`.
diag_mod(cells(H, T),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say([H|T]) => back([H|T]) ] ],
    [ id ==> back([Y|Ys]), type ==> neutral, arcs ==> [ empty : empty => fs([Y|Ys], Ys) ] ],
    [ id ==> back(_), type ==> neutral, arcs ==> [ empty : empty => fs(none, none) ] ],
    [ id ==> fs(_, _), type ==> final ]
  ],
  []
).

% A condition on a compound that evaluates (`N + 1`): not a native value,
% the machine's condition decides it.
diag_mod(sums(N),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => (N + 1 == 3 -> fs(yes) ; otherwise -> fs(took(N, [N]))) ] ],
    [ id ==> fs(took(M, [M])), type ==> neutral, arcs ==> [ empty : empty => fs(M) ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  []
).

% Output arguments pushed natively (issue 37, `codegen::native::call`): a
% fresh variable of the caller (`J`) given to a parameter the callee never
% reads and binds in every final's `diag_mod` is passed as no term
% (`Ground::OUT`); the callee's final hands the value back in its frame's
% output slot and the caller's exit arcs read it. The other ways fall back
% to the machine's call: a variable given twice (`two(N, S, S)`, agreeing or
% not), one inside an argument (`wrap(N, f(X))`), an output the callee leaves
% unbound (`maybe`), a start value that does not convert (`outs(2, 2.5)`).
% `louder` performs an action while its caller waits: the native frames
% become the machine's there (the caller's fresh variable made then).
diag_mod(outs(Max, Start),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => loop(Start) ] ],
    [ id ==> loop(I), type ==> recursive, embedded_dm ==> plus(I, 1, J),
      arcs ==> [ sum(_) : empty => (J >= Max -> loud(J) ; otherwise -> loop(J)) ] ],
    [ id ==> loud(N), type ==> recursive, embedded_dm ==> louder(N, L),
      arcs ==> [ said : empty => shared(L) ] ],
    [ id ==> shared(N), type ==> recursive, embedded_dm ==> two(N, S, S),
      arcs ==> [ two : empty => partly(S) ] ],
    [ id ==> partly(N), type ==> recursive, embedded_dm ==> wrap(N, f(X)),
      arcs ==> [ wrapped : say(X) => unbound(X) ] ],
    [ id ==> unbound(X), type ==> recursive, embedded_dm ==> maybe(X, Y),
      arcs ==> [ m : empty => fs(Y) ] ],
    [ id ==> fs(_), type ==> final ]
  ],
  []
).

diag_mod(plus(A, B, C),
  [ [ id ==> calc, type ==> neutral, arcs ==> [ empty : [S is A + B] => sum(S) ] ],
    [ id ==> sum(S), type ==> final, diag_mod ==> plus(A, B, S) ]
  ],
  []
).

% An action performed while the caller waits for the output: the native
% frames made the machine's (the caller's fresh variable made then).
diag_mod(louder(A, Out),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(A) => said ] ],
    [ id ==> said, type ==> final, diag_mod ==> louder(A, A) ]
  ],
  []
).

diag_mod(two(A, X, Y),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => two ] ],
    [ id ==> two, type ==> final, diag_mod ==> two(A, A, A) ]
  ],
  []
).

% `two` with outputs that differ: the machine's error where both are one
% variable (`split(1)`), two values where they are two (`split(2)`).
diag_mod(split(K),
  [ [ id ==> c, type ==> recursive, embedded_dm ==> (K == 1 -> apart(K, S, S) ; otherwise -> apart(K, S, T)),
      arcs ==> [ two : say(S) => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

diag_mod(apart(A, X, Y),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : [B is A + 1] => two(B) ] ],
    [ id ==> two(B), type ==> final, diag_mod ==> apart(A, A, B) ]
  ],
  []
).

diag_mod(wrap(A, W),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => wrapped ] ],
    [ id ==> wrapped, type ==> final, diag_mod ==> wrap(A, f(A)) ]
  ],
  []
).

diag_mod(maybe(A, Out),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => m ] ],
    [ id ==> m, type ==> final ]
  ],
  []
).

% A list walked as a cursor (`walk([P|Ps]) => walk(Ps)`, the variant holding
% the list alone) with a catch-all situation after it, so that the selection
% has no hand-over fallback: each step of the walk still counts as a
% transition with the history kept or not.
diag_mod(tail(L),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => walk(L) ] ],
    [ id ==> walk([P|Ps]), type ==> neutral, arcs ==> [ empty : empty => walk(Ps) ] ],
    [ id ==> walk(_), type ==> neutral, arcs ==> [ empty : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).

% Lists of atoms and of ints, constants of the DM, walked as cursors (the
% variant holds the list alone): each element said, the history kept or not.
diag_mod(consts(K),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => (K == 1 -> atoms([a, b, c]) ; otherwise -> ints([1, 2, 3])) ] ],
    [ id ==> atoms([P|Ps]), type ==> neutral, arcs ==> [ empty : say(P) => atoms(Ps) ] ],
    [ id ==> atoms([]), type ==> neutral, arcs ==> [ empty : empty => fs ] ],
    [ id ==> ints([N|Ns]), type ==> neutral, arcs ==> [ empty : say(N) => ints(Ns) ] ],
    [ id ==> ints([]), type ==> neutral, arcs ==> [ empty : empty => fs ] ],
    [ id ==> fs, type ==> final ]
  ],
  []
).
