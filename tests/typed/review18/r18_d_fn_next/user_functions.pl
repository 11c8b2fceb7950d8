% The next situation of a walk: found at the target, else the rest. Two
% bad places for the agreement test (`typed::review18::fn_next_agrees`):
% at `boom` the function fails, at `odd` it names no situation of the DM.
route(P, _, _) :- P == boom, !, fail.
route(P, _, _) :- P == odd, !, assign_func_value(nowhere_at_all).
route(P, _, T) :- P == T, !, assign_func_value(found(P)).
route(_, Ps, _) :- assign_func_value(walk(Ps)).
