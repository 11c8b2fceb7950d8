% A recursive situation whose in_arg is a pattern (helper nrec16): its
% variables read natively where the pipe is (a term or held as native
% values), kept in the waiting variant for the exit arcs and the call,
% and given to the machine's instance when the waiting frame becomes the
% machine's (a callee that says something, a history kept).

% The pair `N-Lim` matched by the recursive situation itself; the callee
% counts (`M is N + 1`), the exit arc compares.
diag_mod(main(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 1-Max, arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> N-Lim, embedded_dm ==> count,
      arcs ==> [ counted : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(count,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-L, out_arg ==> M-L,
      arcs ==> [ empty : [M is N + 1] => counted ] ],
    [ id ==> counted, type ==> final ]
  ],
  []
).

% A record `lim(N, L)` whose count the call reads (`bump(N)`), the callee
% saying it (the waiting frame made the machine's); the exit arc hands a
% record built from the pattern's variables back (`out_arg`).
diag_mod(record(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> lim(0, Max), arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> lim(N, L), embedded_dm ==> bump(N),
      arcs ==> [ bumped(M) : empty => (M < L -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(bump(K),
  [ [ id ==> step, type ==> neutral, in_arg ==> lim(_, L), out_arg ==> lim(M, L),
      arcs ==> [ empty : [M is K + 1, say(M)] => bumped(M) ] ],
    [ id ==> bumped(_), type ==> final ]
  ],
  []
).

% A variable twice (`X-X`): the pipe's two parts must be equal; the
% callee makes them differ at the third call (a mismatch: the machine's
% error, or skipped under `skip_unmatched_in_arg`).
diag_mod(twice(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-0, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(K), type ==> recursive, in_arg ==> X-X, embedded_dm ==> same,
      arcs ==> [ done : [J is K + 1] => (J < Max -> ask(J) ; otherwise -> over(X)) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

diag_mod(same,
  [ [ id ==> step, type ==> neutral, in_arg ==> A-B,
      arcs ==> [ empty : empty => (A < 2 -> up ; otherwise -> off) ] ],
    [ id ==> up, type ==> neutral, in_arg ==> A-B, out_arg ==> C-D,
      arcs ==> [ empty : [C is A + 1, D is B + 1] => done ] ],
    [ id ==> off, type ==> neutral, in_arg ==> A-B, out_arg ==> C-B,
      arcs ==> [ empty : [C is A + 1] => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% Parts that are a list: `[N, L]` and `N-[First|_]`.
diag_mod(listed(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> [1, Max], arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> [N, L], embedded_dm ==> step_list,
      arcs ==> [ stepped : empty => (N < L -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(step_list,
  [ [ id ==> step, type ==> neutral, in_arg ==> [N, L], out_arg ==> [M, L],
      arcs ==> [ empty : [M is N + 1] => stepped ] ],
    [ id ==> stepped, type ==> final ]
  ],
  []
).

diag_mod(headed(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0-[a, b], arcs ==> [ empty : empty => ask ] ],
    [ id ==> ask, type ==> recursive, in_arg ==> N-[First|_], embedded_dm ==> rotate,
      arcs ==> [ turned : empty => (N < Max -> ask ; otherwise -> over(First)) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

diag_mod(rotate,
  [ [ id ==> step, type ==> neutral, in_arg ==> N-[H|T], out_arg ==> M-R,
      arcs ==> [ empty : [M is N + 1, append(T, [H], R)] => turned ] ],
    [ id ==> turned, type ==> final ]
  ],
  []
).

% The pipe from the command line matched by the recursive situation.
diag_mod(entry,
  [ [ id ==> ask, type ==> recursive, in_arg ==> N-Lim, embedded_dm ==> count,
      arcs ==> [ counted : empty => (N < Lim -> ask ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).
