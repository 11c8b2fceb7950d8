% Helper nnext23 (issue 37): other definitions of `tests/typed/nnext23`'s
% functions, for an engine that does not hold the forms compiled there.
% `hop/3`: another plain form (the target's clause answers `far`).
hop(X, _, _) :- X == stop, !, fail.
hop(X, _, _) :- X == odd, !, assign_func_value(elsewhere).
hop(X, _, T) :- X == T, !, assign_func_value(far(X, T)).
hop(X, _, _) :- X == mark, !, assign_func_value(done).
hop(_, Xs, _) :- assign_func_value(step(Xs)).

% `next/2`: not plain here (`atom/1`).
next([], _) :- assign_func_value(none).
next([X|Xs], T) :- atom(X), X == T, !, assign_func_value(at(X, Xs)).
next([_|Xs], _) :- assign_func_value(more(Xs)).

% `kind/1`: the same form.
kind(X) :- X < 10, !, assign_func_value(small).
kind(X) :- X > 100, !, assign_func_value(big).
kind(X) :- assign_func_value(mid(X)).

% `wrap/1`: another compound.
wrap(X) :- assign_func_value(v(X)).
