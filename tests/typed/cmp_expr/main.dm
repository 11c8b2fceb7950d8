% Comparisons whose operands are arithmetic expressions (helper nwait17):
% computed as ints in native code, the machine's comparison where an
% operand is no int (a float, an atom) or an operation overflows.

% The count against the limit, both sides expressions; then `=:=`, `=\=`
% and unary minus on expressions of the count and the limit.
diag_mod(main(Max),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => ask(0) ] ],
    [ id ==> ask(I), type ==> recursive, embedded_dm ==> tick,
      arcs ==> [ ticked : [J is I + 1] => (J * 2 < Max * 2 -> ask(J) ; otherwise -> check(J)) ] ],
    [ id ==> check(K), type ==> neutral,
      arcs ==> [ empty : empty => (K - 1 =:= Max - 1 -> same(K) ; otherwise -> diff(K)) ] ],
    [ id ==> same(K), type ==> neutral,
      arcs ==> [ empty : empty => (-K =\= -Max -> over(ne) ; otherwise -> over(eq)) ] ],
    [ id ==> diff(_), type ==> final ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

diag_mod(tick,
  [ [ id ==> step, type ==> neutral, arcs ==> [ empty : empty => ticked ] ],
    [ id ==> ticked, type ==> final ]
  ],
  []
).

% An int expression against itself doubled (overflows at 2^62), against a
% float constant, and in an out_arg's condition.
diag_mod(big(N),
  [ [ id ==> s, type ==> neutral,
      arcs ==> [ empty : empty => (N * 2 > N -> t(pos) ; otherwise -> t(neg)) ] ],
    [ id ==> t(X), type ==> neutral,
      arcs ==> [ empty : [say(X)] => (N + 1 > 1.5 -> u(above) ; otherwise -> u(below)) ] ],
    [ id ==> u(Y), type ==> neutral, out_arg ==> (N - 1 >= 0 -> Y ; otherwise -> none),
      arcs ==> [ empty : [say(Y)] => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).
