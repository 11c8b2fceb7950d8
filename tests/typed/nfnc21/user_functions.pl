% Helper nfnc21 (issue 37): plain functions (several clauses, guards, `is`,
% lists) called by native code, and functions that are not plain.
% `step/3`: a walk's next situation (a duplicate skipped by a head pattern).
step(P, _, _) :- P == boom, !, fail.
step(P, Ps, T) :- P == T, !, assign_func_value(found(P, Ps)).
step(P, Ps, _) :- P == skip, !, assign_func_value(walk(Ps)).
step(P, [Q|Qs], _) :- P == Q, !, assign_func_value(walk(Qs)).
step(_, Ps, _) :- assign_func_value(walk(Ps)).

% `same/2`: a condition's value.
same(A, B) :- A == B, !, assign_func_value(yes).
same(A, _) :- A == boom, !, fail.
same(_, _) :- assign_func_value(no).

% `score/2`: arithmetic, a list as the value.
score(N, _) :- N > 100, !, assign_func_value(big).
score(N, K) :- M is N * K + 1, M mod 2 =:= 0, !, assign_func_value(even(M)).
score(N, K) :- M is N * K + 1, assign_func_value(odd([M, N])).

% `grow/1`: an out_arg's value; fails at 7, assigns nothing at 8, an atom
% at 9 (a type error at the next call).
grow(X) :- X >= 3, X < 5, !, Y is X * 10, assign_func_value(Y).
grow(X) :- X =:= 7, !, fail.
grow(X) :- X =:= 8, !.
grow(X) :- X =:= 9, !, assign_func_value(nine).
grow(X) :- Y is X + 1, assign_func_value(Y).

% Not plain: a clause calls `atom/1` (`wrap/1`); the value is unbound
% (`hole/1`).
wrap(X) :- atom(X), !, assign_func_value(atom).
wrap(X) :- Y is X + 1, assign_func_value(Y).
hole(X) :- X > 100, !, assign_func_value(_).
hole(X) :- Y is X + 2, assign_func_value(Y).
