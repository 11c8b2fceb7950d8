% `shape(Op, X)`: compounds and lists taken (head patterns) and returned
% (built of the head's variables and constants), and the cases the
% engine decides: no clause, a failure after a cut, a type error, no value.
shape(wrap, X) :- assign_func_value(w(X)).
shape(pair, X) :- assign_func_value(X-[X, 1|end]).
shape(head, [H|_]) :- assign_func_value(H).
shape(tail, [_|T]) :- assign_func_value(T).
shape(at, at(R, O)) :- assign_func_value(O-R).
shape(same, X) :- X == f(a, [1]), !, assign_func_value(yes).
shape(same, X) :- f(a, [1]) \== X, assign_func_value(no).
shape(bind, X) :- Y = g(X), Y \== g(b), assign_func_value(Y).
shape(bind, X) :- Y = g(X), assign_func_value([Y, Y]).
shape(cut, X) :- X == boom, !, fail.
shape(cut, _) :- assign_func_value(kept).
shape(err, X) :- Y is X + 1, assign_func_value(f(Y)).
shape(novalue, _).
shape(twice, X) :- assign_func_value(first(X)), assign_func_value(second(X)).
shape(nil, _) :- assign_func_value([]).

% The next situation of `trip/2`'s walk: found at the target; `bad` gives
% a non-list, `improper` an improper list, `skip` a list with a new head,
% `jump` skips one more place, `err` a type error, `boom` fails.
step(P, _, T) :- P == T, !, assign_func_value(found(P)).
step(P, _, _) :- P == bad, !, assign_func_value(walk(oops)).
step(P, Ps, _) :- P == improper, !, assign_func_value(walk([x|y])).
step(P, Ps, _) :- P == skip, !, assign_func_value(walk([x|Ps])).
step(P, [_|Ps], _) :- P == jump, !, assign_func_value(walk(Ps)).
step(P, _, _) :- P == err, !, X is P + 1, assign_func_value(X).
step(P, _, _) :- P == boom, !, fail.
step(_, Ps, _) :- assign_func_value(walk(Ps)).
