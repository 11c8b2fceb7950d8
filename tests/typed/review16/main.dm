% Review of session 15's merge (helper review16): each DM is run by a
% `typed::review16_*` test, compiled and plans against the interpreter.

% 1. A variable in_arg on a recursive situation whose call reads it and
% whose exit arcs do not (`in_arg ==> X, embedded_dm ==> shout(X)`): the
% callee says its argument before and after a frame is made the
% machine's.
diag_mod(vcall,
  [ [ id ==> start, type ==> neutral, out_arg ==> 7, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> X, embedded_dm ==> shout(X),
      arcs ==> [ shouted : empty => over ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(shout(K),
  [ [ id ==> one, type ==> neutral,
      arcs ==> [ empty : [J is K + 1, say(J)] => two ] ],
    [ id ==> two, type ==> neutral,
      arcs ==> [ empty : [say(again(K))] => three ] ],
    [ id ==> three, type ==> neutral,
      arcs ==> [ empty : [M is K * 4611686018427387904, say(M)] => shouted ] ],
    [ id ==> shouted, type ==> final ]
  ],
  []
).

% The same looped: the exit arc goes back to `ask` three times.
diag_mod(vloop,
  [ [ id ==> start, type ==> neutral, out_arg ==> 5, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> X, embedded_dm ==> quiet(X),
      arcs ==> [ said : empty => d(inc(k, _)) ] ],
    [ id ==> d(K), type ==> neutral,
      arcs ==> [ empty : empty => (K < 3 -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(quiet(K),
  [ [ id ==> one, type ==> neutral,
      arcs ==> [ empty : empty => two ] ],
    [ id ==> two, type ==> neutral,
      arcs ==> [ empty : [M is K + 1, say(M)] => said ] ],
    [ id ==> said, type ==> final ]
  ],
  []
).

% 2. An `inc` that overflows in the next situation of a recursive
% situation's exit arc, of an arc with an action, of a first arc.
diag_mod(xbig,
  [ [ id ==> c, type ==> recursive, embedded_dm ==> one,
      arcs ==> [ done : empty => d(inc(n, _)) ] ],
    [ id ==> d(A), type ==> neutral, arcs ==> [ empty : empty => (A < 0 -> fin ; otherwise -> c) ] ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 9223372036854775804 ]
).

diag_mod(one,
  [ [ id ==> s, type ==> neutral, arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(xout,
  [ [ id ==> c, type ==> recursive, embedded_dm ==> one, out_arg ==> inc(n, _),
      arcs ==> [ done : empty => d ] ],
    [ id ==> d, type ==> neutral, in_arg ==> A, arcs ==> [ empty : empty => (A < 0 -> fin ; otherwise -> c) ] ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 9223372036854775804 ]
).

diag_mod(sbig,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : [say(hi)] => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral, arcs ==> [ empty : [say(ho)] => (A < 0 -> fin ; otherwise -> s) ] ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 9223372036854775804 ]
).

diag_mod(gbig,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral, arcs ==> [ empty : [say(ho)] => (A < 0 -> fin ; otherwise -> s) ] ],
    [ id ==> fin, type ==> final ]
  ],
  [ n ==> 9223372036854775804 ]
).

% 3. `inc` of a local inside `when/3`'s branches (both evaluated) in a
% next situation and an out_arg.
diag_mod(wpick(V),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => s(1) ] ],
    [ id ==> s(X), type ==> neutral,
      out_arg ==> apply(when(_, _, _), [X > 2, inc(n, _), inc(m, _)]),
      arcs ==> [ empty : empty => t(apply(when(_, _, _), [X < 2, inc(n, _), inc(m, _)]), get(n, _), get(m, _)) ] ],
    [ id ==> t(A, B, C), type ==> neutral, in_arg ==> P,
      out_arg ==> f(inc(n, _), apply(when(_, _, _), [A > 12, inc(m, _), get(n, _)]), get(m, _)),
      arcs ==> [ empty : empty => (B < V -> s(B) ; otherwise -> fin(A, B, C, P)) ] ],
    [ id ==> fin(_, _, _, _), type ==> final ]
  ],
  [ n ==> 0, m ==> 10 ]
).

% 4. An in_arg pattern the pipe does not match, skipped: a recursive
% situation (native, nrec16) visited three times; a held pipe of another
% shape matched by a recursive situation and by a neutral one.
diag_mod(rskip,
  [ [ id ==> start, type ==> neutral, out_arg ==> x, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> _N-_L, embedded_dm ==> one,
      arcs ==> [ done : empty => d(inc(k, _)) ] ],
    [ id ==> d(K), type ==> neutral,
      arcs ==> [ empty : empty => (K < 3 -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(hskip,
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-5, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, embedded_dm ==> pair,
      arcs ==> [ added : empty => rec ] ],
    [ id ==> rec, type ==> recursive, in_arg ==> lim(N, L), embedded_dm ==> one,
      arcs ==> [ done : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> f(N, L),
      arcs ==> [ empty : empty => d(inc(k, _)) ] ],
    [ id ==> d(K), type ==> neutral,
      arcs ==> [ empty : empty => (K < 3 -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(pair,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => added ] ],
    [ id ==> added, type ==> final ]
  ],
  []
).

% 5. A global of type int that a user function sets to a float
% (`pokef(_)`: `gf` := 2.5), then counted by `inc` in a next situation
% (`gfloat`) and in an out_arg (`gfout`): the machine's `inc` gives 3.5.
diag_mod(gfloat,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : [apply(pokef(_), [x])] => t(inc(gf, _)) ] ],
    [ id ==> t(_), type ==> final ]
  ],
  []
).

diag_mod(gfout,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(gf, _),
      arcs ==> [ empty : [apply(pokef(_), [x])] => t ] ],
    [ id ==> t, type ==> final ]
  ],
  []
).

diag_mod(gfloop,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : empty => t(inc(gf, _)) ] ],
    [ id ==> t(N), type ==> neutral,
      arcs ==> [ empty : [apply(pokef(_), [x])] => (N < 3 -> s ; otherwise -> fin(N)) ] ],
    [ id ==> fin(_), type ==> final ]
  ],
  []
).

% The same global read by `get` in a next situation beside a local's
% `inc` (`gget`: nfx16's `nat_ev_effects`) and in a condition (`gcond`).
diag_mod(gget,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : [apply(pokef(_), [x])] => t(inc(n, _), get(gf, _)) ] ],
    [ id ==> t(_, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

diag_mod(gcond,
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : [apply(pokef(_), [x])] => (get(gf, _) < 3 -> low ; otherwise -> high) ] ],
    [ id ==> low, type ==> final ],
    [ id ==> high, type ==> final ]
  ],
  []
).

% A local int a user function sets to a float (`pokel(_)`: `n` := 2.5),
% then counted by `inc` in a next situation and an out_arg.
diag_mod(lfloat,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : [apply(pokel(_), [x])] => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral, in_arg ==> P, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => fin(A, P) ] ],
    [ id ==> fin(_, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

% 6. A recursive situation whose in_arg pattern's variables the call, the
% exit arc's action, its next situation and the out_arg read, the callee
% saying something (its frames made the machine's), a DM parameter in
% the pattern, an id variable in it.
diag_mod(rout(Lim),
  [ [ id ==> start, type ==> neutral, out_arg ==> 1-Lim, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(K), type ==> recursive, in_arg ==> N-Lim, embedded_dm ==> talk(N), out_arg ==> M-Lim,
      arcs ==> [ talked(T) : [M is N + T, say(K)] => (M < Lim -> ask(N) ; otherwise -> over(N, K)) ] ],
    [ id ==> over(_, _), type ==> final ]
  ],
  []
).

diag_mod(talk(X),
  [ [ id ==> s, type ==> neutral, arcs ==> [ empty : [say(X)] => talked(1) ] ],
    [ id ==> talked(_), type ==> final ]
  ],
  []
).

diag_mod(rid,
  [ [ id ==> start, type ==> neutral, out_arg ==> 2-5, arcs ==> [ empty : empty => ask(2) ] ],
    [ id ==> ask(K), type ==> recursive, in_arg ==> K-L, embedded_dm ==> talk(L), out_arg ==> J-L,
      arcs ==> [ talked(_) : [J is K + 1] => (J < L -> ask(J) ; otherwise -> over(J)) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

% 7. An `inc` that overflows in a callee's next situation and out_arg,
% the callee's frame on the native stack above its caller's (one and two
% levels).
diag_mod(cbig,
  [ [ id ==> c, type ==> recursive, embedded_dm ==> xb,
      arcs ==> [ done : empty => d ] ],
    [ id ==> d, type ==> neutral, in_arg ==> P, arcs ==> [ empty : [say(back)] => (P < 0 -> fin ; otherwise -> c) ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

diag_mod(cbig2,
  [ [ id ==> c, type ==> recursive, embedded_dm ==> cbig,
      arcs ==> [ fin : empty => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  [ k ==> 0 ]
).

diag_mod(xb,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : [say(x)] => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral, arcs ==> [ empty : empty => (A < 0 -> done ; otherwise -> s) ] ],
    [ id ==> done, type ==> final ]
  ],
  [ n ==> 9223372036854775800 ]
).
