% User functions of `main.dm` (helper `nfun18`).
:- dynamic(cnt/1).
cnt(0).

% tag_of(_): the value of the SitLog variable `tag` (a local of the
% running DM first, else the global).
tag_of(_) :- var_op(get(tag, V)), assign_func_value(V).

% reset(_): the counter back to 0 (each run starts with it; the tests
% share one engine).
reset(_) :- retractall(cnt(_)), assert(cnt(0)), assign_func_value(reset).

% counter(_): 1, 2, 3, ... across calls (state kept by `assert`).
counter(_) :- retract(cnt(N)), M is N + 1, assert(cnt(M)), assign_func_value(M).

fails(_) :- fail.

throws(_) :- throw(oops).

unbound(_) :- assign_func_value(_).

shape(X) :- assign_func_value(f(X, [1|_])).

% hist(_): how many entries the running DM's history has.
hist(_) :- get_history(H), length(H, L), assign_func_value(L).

nowhere(_) :- var_op(get(nowhere, V)), assign_func_value(V).
