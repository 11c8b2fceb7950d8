% Helper nplain20: plain functions whose values native code selects or
% compares, and the calls the engine decides: a failure (`boom`), no value
% (`quiet`), a value no situation has (`lost`), a type error, an overflow.
next_of(P, _, _) :- P == boom, !, fail.
next_of(P, _, _) :- P == quiet, !.
next_of(P, _, T) :- P == T, !, assign_func_value(found(P)).
next_of(P, _, _) :- P == lost, !, assign_func_value(elsewhere(P)).
next_of(P, _, _) :- P == stop, !, assign_func_value(nowhere).
next_of(P, Ps, _) :- P == skip, !, assign_func_value(walk([x|Ps])).
next_of(_, Ps, _) :- assign_func_value(walk(Ps)).

is_at(P, _) :- P == boom, !, fail.
is_at(P, _) :- P == quiet, !.
is_at(P, T) :- P == T, !, assign_func_value(yes).
is_at(P, _) :- P == num, !, assign_func_value(1).
is_at(_, _) :- assign_func_value(no).

bump(N) :- M is N + 1, M > 3, !, assign_func_value(done(M)).
bump(N) :- M is N + 1, assign_func_value(at(M)).

% An if-then-else whose condition tests (plain): yes from 1000 on, no
% below; 13 cuts in the then branch and then fails; a negative weight
% fails; `big` gives a nested if-then-else's value.
heavy(W) :-
    W >= 0,
    (   W >= 1000
    ->  A = yes
    ;   W =:= 13
    ->  A = unlucky, !, fail
    ;   A = no
    ),
    assign_func_value(A).
