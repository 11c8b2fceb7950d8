% Helper review19: `heavy(W)` is `yes` for a weight of at least 1000, `no`
% for a smaller one; it fails for a negative weight (no value: an error of
% the call).
heavy(W) :-
    W >= 0,
    (   W >= 1000
    ->  A = yes
    ;   A = no
    ),
    assign_func_value(A).
