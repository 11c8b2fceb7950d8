double(X) :-
    Y is X * 2,
    assign_func_value(Y).
add(X, Y) :-
    Z is X + Y,
    assign_func_value(Z).
