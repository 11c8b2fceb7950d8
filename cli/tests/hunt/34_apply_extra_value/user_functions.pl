% double(X): twice X.
double(X) :-
    Y is X * 2,
    assign_func_value(Y).
