% Helper review22: `reaches(X, F)` is `yes` when the reading X is at or
% above the floor F, `no` below it.
reaches(X, F) :- X >= F, !, assign_func_value(yes).
reaches(_, _) :- assign_func_value(no).
