% Helper nrs22 (issue 37): other definitions of `tests/typed/nrs22`'s
% functions, for an engine that does not hold the forms compiled there.
% `classify/1`: another plain form.
classify(N) :- N < 0, !, assign_func_value(nothing).
classify(0) :- !, assign_func_value(small).
classify(N) :- N > 1000000, !, assign_func_value(big).
classify(_) :- assign_func_value(other).

% `pick/2`: not plain here (`atom/1`).
pick([], _) :- assign_func_value(empty).
pick([X|Xs], X) :- !, assign_func_value(hit(Xs)).
pick([X|_], _) :- atom(X), X == skip, !, assign_func_value(skipped).
pick([_|Xs], _) :- assign_func_value(rest(Xs)).

% `diff/2`: the same form.
diff(X, Y) :- X == Y, !, assign_func_value(q(same)).
diff(X, Y) :- Z is max(X, Y) - min(X, Y) + abs(X) rem 7, W is -Z, assign_func_value(p(Z, W)).

% `area/1`: the same clauses but one constant.
area(rect(W, H)) :- A is W * H, assign_func_value(A).
area(sq(S)) :- A is S * S + 3, assign_func_value(A).
area(_) :- assign_func_value(unknown).

quot(X, Y) :- Q is X // Y, assign_func_value(Q).

% `nope/1`: succeeds here.
nope(_) :- assign_func_value(yes).

wrapn(X) :- atom(X), !, assign_func_value(X).
wrapn(X) :- assign_func_value(n(X)).

% `step/1`: another arithmetic.
step(X) :- Y is X + 1000, assign_func_value(Y).
