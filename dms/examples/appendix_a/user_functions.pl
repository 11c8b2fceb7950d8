% User functions of the Appendix A example, written for sitlog-rs from
% the description of Listing A5 in the 2021 SitLog paper (plus `when`,
% which the out_arg of main's `is` uses but the paper does not list).
%
% A user function is called from L as apply(Goal, Args); it reports its
% value with assign_func_value/1, reads and writes SitLog variables with
% var_op/1 and reads the task history with get_history/1.

% f(X): ok when X is the current value of the local `day`, else 'not ok'.
f(X) :-
    var_op(get(day, Day)),
    (   X == Day
    ->  Answer = ok
    ;   Answer = 'not ok'
    ),
    assign_func_value(Answer).

% g(_): the last transition (Expectation:Action) of the current DM.
g(_) :-
    get_history(History),
    get_last_transition(History, Transition),
    assign_func_value(Transition).

% h(X, Y): the next situation: back to `is` when X and Y are the same,
% to the recursive situation `rs` otherwise.
h(X, Y) :-
    (   X == Y
    ->  Next = is
    ;   Next = rs
    ),
    assign_func_value(Next).

% when(Cond, Then, Else): Then if Cond (evaluated: `true` or `false` for
% `==`) holds when called as a goal, else Else.
when(Cond, Then, Else) :-
    (   call(Cond)
    ->  Value = Then
    ;   Value = Else
    ),
    assign_func_value(Value).
