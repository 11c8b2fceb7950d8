when(Cond, Then, Else) :-
    (   Cond == true
    ->  assign_func_value(Then)
    ;   assign_func_value(Else)
    ).
