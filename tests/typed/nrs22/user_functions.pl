% Helper nrs22 (issue 37): plain functions compiled to Rust.
% `classify/1`: guards, a cut then `fail`, `is` (an overflow), a cut inside
% an if-then-else then a failure.
classify(N) :- N < 0, !, fail.
classify(0) :- !, assign_func_value(zero).
classify(N) :- N > 1000000, !, M is N * N, assign_func_value(huge(M)).
classify(N) :- R is N mod 3, R =:= 0, N > 20, !, D is N // 3, assign_func_value(third(D)).
classify(N) :- ( N > 10 -> !, K = big ; K = small ), N =\= 13, N =\= 4, assign_func_value(K).
classify(_) :- assign_func_value(other).

% `pick/2`: list head patterns, a value built of the rest, `=` and `\==`,
% the last assignment winning (in an if-then-else).
pick([], _) :- assign_func_value(empty).
pick([X|Xs], X) :- !, assign_func_value(hit(Xs)).
pick([X, Y|_], T) :- X \== T, Y == T, !, L = [Y, X], assign_func_value(second(L)).
pick([X|Xs], _) :- assign_func_value(rest(Xs)), ( X == skip -> assign_func_value(skipped) ; true ).

% `diff/2`: min, max, abs, rem, unary minus, a compound of two integers.
diff(X, Y) :- X == Y, !, assign_func_value(q(same)).
diff(X, Y) :- Z is max(X, Y) - min(X, Y) + abs(X) rem 7, W is -Z, assign_func_value(p(Z, W)).

% `area/1`: compound head patterns; an integer compared.
area(rect(W, H)) :- A is W * H, assign_func_value(A).
area(sq(S)) :- A is S * S, assign_func_value(A).
area(_) :- assign_func_value(unknown).

% `quot/2`: division by zero, a type error.
quot(X, Y) :- Q is X // Y, assign_func_value(Q).

% `nope/1`: fails.
nope(_) :- fail.

% `wrapn/1`: not plain (`atom/1`).
wrapn(X) :- atom(X), !, assign_func_value(X).
wrapn(X) :- assign_func_value(n(X)).

% `step/1`: an out_arg's value.
step(X) :- X >= 100, !, Y is X - 100, assign_func_value(Y).
step(X) :- Y is X * 3 + 1, assign_func_value(Y).
