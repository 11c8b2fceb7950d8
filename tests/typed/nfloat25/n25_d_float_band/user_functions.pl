% Helper nfloat25: `hit(X)` where half of X's height above the floor Lo
% is at most a quarter, else the rest of the sweep.
inband(X, Lo, _) :- M is (X - Lo) / 2.0, M >= 0.0, M =< 0.25, !, assign_func_value(hit(X)).
inband(_, _, Rest) :- assign_func_value(scan(Rest)).
