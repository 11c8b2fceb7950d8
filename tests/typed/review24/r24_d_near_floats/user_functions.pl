% Helper review24: `near(X, T)` is `close` when the float X is within a
% tenth of T, `far` otherwise.
near(X, T) :- D is abs(X - T), D < 0.1, !, assign_func_value(close).
near(_, _) :- assign_func_value(far).
