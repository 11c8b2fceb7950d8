% Helper nmemo25: the action of a walk's exit arc, a user function (native
% code hands such a visit to the machine, from the situation's template).
note(_) :- assign_func_value(empty).
