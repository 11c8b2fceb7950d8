% Helper ngauge25 (issue 37): an out_arg whose variable an arc leaves
% unbound passes the pipe on unchanged (D-18); in a recursive situation
% that is the pipe the embedded DM handed back (D-22). Variants: bound on
% some exit arcs, on none, on all; a neutral situation; a final; the
% variable bound later by the next situation's selection (D-21) on some
% paths; the variable named by the action; the in_arg's own variable.

% The callee: `a` above 5, `b` above 0, else `c`, which sets the pipe.
diag_mod(pick(R),
  [ [ id ==> p, type ==> neutral,
      arcs ==> [ empty : empty => (R > 5 -> a ; otherwise -> (R > 0 -> b ; otherwise -> c)) ] ],
    [ id ==> a, type ==> final ],
    [ id ==> b, type ==> final ],
    [ id ==> c, type ==> final, out_arg ==> from_c ]
  ],
  []
).

% Bound on two exit arcs of three (as `r24_d_gauge_guard`).
diag_mod(rec_some(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => w ] ],
    [ id ==> w, type ==> recursive, in_arg ==> R, out_arg ==> R1,
      embedded_dm ==> pick(R),
      arcs ==> [ a : [R1 is R - 2] => w,
                 b : [R1 is R - 1] => (R1 > 0 -> w ; otherwise -> done),
                 c : say([left, R]) => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% Bound on no exit arc: the count in the id, the pipe the callee's.
diag_mod(rec_none(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => w(0) ] ],
    [ id ==> w(I), type ==> recursive, in_arg ==> R, out_arg ==> R1,
      embedded_dm ==> pick(R),
      arcs ==> [ a : [J is I + 1] => (J < 3 -> w(J) ; otherwise -> done),
                 b : [J is I + 1] => (J < 3 -> w(J) ; otherwise -> done),
                 c : [J is I + 1] => (J < 3 -> w(J) ; otherwise -> done) ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% Bound on every exit arc.
diag_mod(rec_all(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => w ] ],
    [ id ==> w, type ==> recursive, in_arg ==> R, out_arg ==> R1,
      embedded_dm ==> pick(R),
      arcs ==> [ a : [R1 is R - 2] => w,
                 b : [R1 is R - 1] => (R1 > 0 -> w ; otherwise -> done),
                 c : [R1 is R] => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% The variable named by an exit arc's action (read, not bound).
diag_mod(rec_said(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => w ] ],
    [ id ==> w, type ==> recursive, in_arg ==> R, out_arg ==> R1,
      embedded_dm ==> pick(R),
      arcs ==> [ a : [R1 is R - 2] => w,
                 b : [R1 is R - 1] => (R1 > 0 -> w ; otherwise -> done),
                 c : say([left, R1]) => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% Neutral situations: the out_arg's variable unbound in the arc.
diag_mod(neu_none(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => s(0) ] ],
    [ id ==> s(I), type ==> neutral, in_arg ==> X, out_arg ==> Y,
      arcs ==> [ empty : [J is I + 1] => (J < 4 -> s(J) ; otherwise -> (X > 0 -> fin ; otherwise -> fin)) ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

% Neutral: bound on one way only (`is` there), and said in the action.
diag_mod(neu_some(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => s(0) ] ],
    [ id ==> s(I), type ==> neutral, in_arg ==> X, out_arg ==> Y,
      arcs ==> [ empty : [J is I + 1] => (J < 4 -> s(J) ; otherwise -> t) ] ],
    [ id ==> t, type ==> neutral, in_arg ==> X, out_arg ==> Y,
      arcs ==> [ empty : [say(Y)] => (X > 2 -> u(Y) ; otherwise -> fin) ] ],
    [ id ==> u(seven), type ==> neutral, arcs ==> [ empty : empty => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

% The out_arg's variable bound later by the next situation (D-21):
% `v(R)` selects `v(7)` when the pipe is above 0, else `v(Z)` leaves it.
diag_mod(neu_later(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => s ] ],
    [ id ==> s, type ==> neutral, in_arg ==> X, out_arg ==> R,
      arcs ==> [ empty : empty => (X > 0 -> v(R) ; otherwise -> w(R)) ] ],
    [ id ==> v(7), type ==> neutral, arcs ==> [ empty : empty => fin ] ],
    [ id ==> w(Z), type ==> neutral, arcs ==> [ empty : empty => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

% A final whose out_arg's variable nothing binds, and one a prog binds.
diag_mod(fin_none(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N,
      arcs ==> [ empty : empty => (N > 0 -> f1 ; otherwise -> f2) ] ],
    [ id ==> f1, type ==> final, out_arg ==> Q ],
    [ id ==> f2, type ==> final, out_arg ==> Q, prog ==> [Q is 5] ]
  ],
  []
).

% Called: a final whose out_arg is unbound hands the caller's pipe back.
diag_mod(fin_called(N),
  [ [ id ==> start, type ==> neutral, out_arg ==> N, arcs ==> [ empty : empty => w ] ],
    [ id ==> w, type ==> recursive, in_arg ==> R, out_arg ==> R1,
      embedded_dm ==> fin_none(R),
      arcs ==> [ f1 : [R1 is R + 100] => done,
                 f2 : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% The in_arg's own variable as the out_arg (the pipe a pattern).
diag_mod(same_var,
  [ [ id ==> s, type ==> neutral, in_arg ==> f(X), out_arg ==> X,
      arcs ==> [ empty : empty => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).
