% Plain functions (run natively where they can) and one that is not.
same(A, B) :- A == B, !, assign_func_value(yes).
same(_, _) :- assign_func_value(no).

next_of(X) :- Y is X + 1, assign_func_value(Y).

calc(add, X, Y) :- Z is X + Y, assign_func_value(Z).
calc(sub, X, Y) :- Z is X - Y, assign_func_value(Z).
calc(mul, X, Y) :- Z is X * Y, assign_func_value(Z).
calc(div, X, Y) :- Z is X // Y, assign_func_value(Z).
calc(mod, X, Y) :- Z is X mod Y, assign_func_value(Z).
calc(rem, X, Y) :- Z is X rem Y, assign_func_value(Z).
calc(minmax, X, Y) :- Z is min(X, Y) - max(X, Y) + abs(X) - -Y + (+ 1), assign_func_value(Z).
calc(cmp, X, Y) :- X < Y, !, assign_func_value(lt).
calc(cmp, X, Y) :- X =:= Y, !, assign_func_value(eq).
calc(cmp, X, Y) :- X > Y, X >= Y, X =\= Y, Y =< X, !, assign_func_value(gt).
calc(cube, X, _) :- Z is X * X * X, assign_func_value(Z).
calc(nothing, X, _) :- X > 1000.
calc(after, X, _) :- assign_func_value(a), X > 1000.
calc(after, _, _).
calc(twice, X, Y) :- assign_func_value(X), assign_func_value(Y).
calc(cutfail, X, _) :- X > 0, !, X > 1000, assign_func_value(big).
calc(cutfail, _, _) :- assign_func_value(small).
calc(pair, X, X) :- !, assign_func_value(same).
calc(pair, X, Y) :- Z = X, Z \== Y, true, assign_func_value(Z).
calc(isb, X, Y) :- X is Y + 0, assign_func_value(yes).
calc(isb, _, _) :- assign_func_value(no).
calc(fails, _, _) :- fail.
calc(fails, _, _) :- false.

% Not plain (a call of another predicate): the engine runs it.
kind_of(X) :- kind(X, K), assign_func_value(K).
kind(X, int) :- integer(X), !.
kind(_, other).
