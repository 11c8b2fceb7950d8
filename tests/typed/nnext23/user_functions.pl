% Helper nnext23 (issue 37): plain functions answering compounds.
% `hop/3`: the next situation of a walk.
hop(X, _, _) :- X == stop, !, fail.
hop(X, _, _) :- X == odd, !, assign_func_value(elsewhere).
hop(X, _, _) :- X == zz, !, assign_func_value(zap(X)).
hop(X, Xs, T) :- X == T, !, assign_func_value(at(X, Xs)).
hop(X, _, _) :- X == mark, !, assign_func_value(done).
hop(X, _, _) :- X == pair, !, N = 3, assign_func_value(far(X, N)).
hop(X, Xs, _) :- X == num, !, K is 2 + 3, assign_func_value(go(K, Xs)).
hop(X, Xs, _) :- X == low, !, assign_func_value(go(1, Xs)).
hop(_, Xs, _) :- assign_func_value(step(Xs)).

% `next/2`: a list head pattern; the last assignment reached wins.
next([], _) :- assign_func_value(none).
next([X|Xs], T) :- X == T, !, assign_func_value(at(X, Xs)).
next([X|Xs], _) :- assign_func_value(more(Xs)), ( X == halt -> assign_func_value(none) ; true ).

% `kind/1`: an atom or a compound.
kind(X) :- X < 10, !, assign_func_value(small).
kind(X) :- X > 100, !, assign_func_value(big).
kind(X) :- assign_func_value(mid(X)).

% `wrap/1`: an out_arg's value, a compound.
wrap(X) :- assign_func_value(w(X, [X])).
