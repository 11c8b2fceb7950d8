% User functions of `main.dm` (helper `nbound20`).
:- dynamic(cnt/1).
cnt(0).

% reset(_): the counter back to 0 (each run starts with it; the tests
% share one engine).
reset(_) :- retractall(cnt(_)), assert(cnt(0)), assign_func_value(reset).

% place_here: where the object is, by call: unknown, then shelf(2), then
% an unbound variable (a value native code does not hold), then
% [shelf, 3], then it fails (an error of the evaluation).
place_here :-
    retract(cnt(N)), M is N + 1, assert(cnt(M)),
    place_at(M, P), assign_func_value(P).

place_at(1, unknown).
place_at(2, shelf(2)).
place_at(3, _).
place_at(4, [shelf, 3]).
