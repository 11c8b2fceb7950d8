% Helper review19: `heavy(W)` is `yes` for a weight of at least 1000, `no`
% for a smaller number.
heavy(W) :-
    (   W >= 1000
    ->  A = yes
    ;   A = no
    ),
    assign_func_value(A).
