greeting(Name) :- assign_func_value(['Hello', Name]).
