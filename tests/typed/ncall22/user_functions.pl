% User functions of `main.dm` (helper `ncall22`).
:- dynamic(cnt/1).
:- dynamic(seen/1).
cnt(0).

% reset(_): the counter back to 0 and no fact seen (each run starts with
% it; the tests share one engine).
reset(_) :-
    retractall(cnt(_)), retractall(seen(_)), assert(cnt(0)),
    assign_func_value(reset).

% tally(S): counts the call, asserts `seen(S)`, gives `S-N`, N the count.
tally(S) :-
    retract(cnt(N)), M is N + 1, assert(cnt(M)), assert(seen(S)),
    assign_func_value(S-M).

% same(S): counts the call, asserts `seen(S)`, gives `S`.
same(S) :-
    retract(cnt(N)), M is N + 1, assert(cnt(M)), assert(seen(S)),
    assign_func_value(S).

% count(_): the calls counted and the facts seen so far.
count(_) :-
    cnt(N), findall(S, seen(S), Ss), assign_func_value(N/Ss).

% hand(X): not plain (it asserts): native code hands the frames over to
% call it. Counts the call too; gives `at(N)`.
hand(X) :-
    retract(cnt(N)), M is N + 1, assert(cnt(M)), assert(seen(hand(X))),
    assign_func_value(at(M)).
