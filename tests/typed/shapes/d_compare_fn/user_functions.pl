% same_place(A, B): yes when the two places are the same, else no.
same_place(A, B) :- A == B, !, assign_func_value(yes).
same_place(_, _) :- assign_func_value(no).
