% Helper nfloat25 (issue 37): plain user functions on floats, run natively
% where the engine would give the same value, else by the engine.
cmp(X, Y) :- X < Y, !, assign_func_value(lt).
cmp(X, Y) :- X =:= Y, !, assign_func_value(eq).
cmp(_, _) :- assign_func_value(gt).
calc(X, Y) :- A is X / Y, B is X - Y * 0.5, C is abs(B), D is max(A, C), E is min(X, Y),
    assign_func_value(r(A, C, D, E)).
idiv(X, Y) :- Z is X // Y, W is X mod Y, assign_func_value(Z-W).
same(X, Y) :- X == Y, !, assign_func_value(yes).
same(_, _) :- assign_func_value(no).
step(X) :- Y is X + 0.1, assign_func_value(at(Y)).
pick(X, Y, Ps) :- X >= Y, !, assign_func_value(walk(Ps)).
pick(_, _, Ps) :- assign_func_value(skip(Ps)).
root(X) :- X >= 0, Y is X * 1.0, assign_func_value(done(Y)).
