% Helper tidy23: an exit arc's action that is a user function (native code
% hands such a call to the machine, from the situation's template).
note(_) :- assign_func_value(empty).
