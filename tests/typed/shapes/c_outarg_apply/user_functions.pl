% succ_of(X): X + 1.
succ_of(X) :- Y is X + 1, assign_func_value(Y).
