% User functions of the cases: `never(X)` fails unless X is `never`,
% `pair_of(X)` is `[X, X]`, `ratio(A, B)` is A / B.
never(X) :- X == never, assign_func_value(yes).
pair_of(X) :- assign_func_value([X, X]).
ratio(A, B) :- V is A / B, assign_func_value(V).
