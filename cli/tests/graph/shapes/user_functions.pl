% choose(X): where a pick leads.
choose(X) :-
    (   X == fast
    ->  Next = quick
    ;   Next = ask_user
    ),
    assign_func_value(Next).

% dec(N): N - 1 (a value the diagram cannot enumerate).
dec(N) :-
    M is N - 1,
    assign_func_value(M).
