% `get(n, _)` and `inc(n, _)` of a local (or a global) in next situations
% and out_args, done by native code once each, in the machine's order: the
% next situation, then the out_arg (`nfx16`). Each DM is run as the main
% one by `typed::a_locals_inc_in_next_and_out_arg_agrees`; a value counted
% twice would change the ids the history and the report show.

% A loop: the next situation counts and reads, the out_arg reads and
% counts (`f(get(n, _), inc(n, _))`), a conditional next situation.
diag_mod(count,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _), get(n, _)) ] ],
    [ id ==> t(A, B), type ==> neutral, in_arg ==> P, out_arg ==> f(get(n, _), inc(n, _)),
      arcs ==> [ empty : empty => (A < 9 -> s ; otherwise -> fin(A, B, P)) ] ],
    [ id ==> fin(_, _, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

% A float local counted (the machine's `inc` of a float).
diag_mod(fcount,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : empty => (A < 6.0 -> s ; otherwise -> fin(A, P)) ] ],
    [ id ==> fin(_, _), type ==> final ]
  ],
  [ n ==> 0.5 ]
).

% The next situation's `inc` overflows (the machine's error).
diag_mod(big,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral,
      arcs ==> [ empty : empty => u(A, inc(n, _)) ] ],
    [ id ==> u(_, _), type ==> final ]
  ],
  [ n ==> 9223372036854775805 ]
).

% The out_arg's `inc` overflows, after the next situation read the value.
diag_mod(big_out,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(get(n, _)) ] ],
    [ id ==> t(_), type ==> final ]
  ],
  [ n ==> 9223372036854775807 ]
).

% A user function sets the local to an atom behind the compiler's back:
% the next situation's `inc` is the machine's error.
diag_mod(poked,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(A), type ==> neutral,
      arcs ==> [ empty : [apply(poke(_), [x])] => u(A, inc(n, _)) ] ],
    [ id ==> u(_, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

% A local set to an atom the caller passes (not its default, and not a constant: with
% `set(n, none)` check's E0242 would refuse the program): `inc` is the machine's error.
diag_mod(atom(V),
  [ [ id ==> s, type ==> neutral, prog ==> [set(n, V)], out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(_), type ==> final ]
  ],
  [ n ==> 0 ]
).

% A value no native situation takes (`t(X)` is term code: its out_arg
% reads `Y` again): handed to the machine as counted, the out_arg the
% machine's, once.
diag_mod(handed,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(n, _),
      arcs ==> [ empty : empty => t(inc(n, _)) ] ],
    [ id ==> t(1), type ==> neutral, in_arg ==> _,
      arcs ==> [ empty : empty => s ] ],
    [ id ==> t(X), type ==> neutral, in_arg ==> P, out_arg ==> g(get(n, Y), Y, P),
      arcs ==> [ empty : empty => (X < 6 -> s ; otherwise -> fin(X, P)) ] ],
    [ id ==> fin(_, _), type ==> final ]
  ],
  [ n ==> 0 ]
).

% Globals: counted in a next situation and an out_arg, then one that
% overflows.
diag_mod(glob,
  [ [ id ==> s, type ==> neutral, out_arg ==> inc(g, _),
      arcs ==> [ empty : empty => t(inc(g, _), get(g, _)) ] ],
    [ id ==> t(A, B), type ==> neutral, in_arg ==> P, out_arg ==> inc(gbig, _),
      arcs ==> [ empty : empty => (A < 5 -> s ; otherwise -> fin(A, B, P)) ] ],
    [ id ==> fin(_, _, _), type ==> final ]
  ],
  []
).

% A DM calling `count` (the callee's frame pushed natively), counting
% its own local in the exit arc's next situation.
diag_mod(calls,
  [ [ id ==> c, type ==> recursive, embedded_dm ==> count,
      arcs ==> [ fin(_, _, _) : empty => d(inc(k, _)) ] ],
    [ id ==> d(K), type ==> neutral, out_arg ==> inc(k, _),
      arcs ==> [ empty : empty => (K < 3 -> c ; otherwise -> e(K)) ] ],
    [ id ==> e(_), type ==> final ]
  ],
  [ k ==> 0 ]
).
