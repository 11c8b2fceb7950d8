% User functions of the supermarket assistant (the 2021 SitLog paper,
% Figure 1 and Sections 7-8), written for sitlog-rs. The language of the
% behaviour library first; then list work for the DMs. The inference
% itself (diagnosis, decision, planning) is Rust: shop_diagnose/4 and
% shop_decide/4, registered by the simulated robot.

:- consult('behaviors/language.pl').

% shop_vocab(+Objects, +Classes): the words the robot understands.
shop_vocab(Objects, Classes) :-
    assign_func_value(vocab([golem], Objects, Classes)).

% lookup(+Key, +Pairs): the value of Key in Key-Value Pairs, or none.
lookup(Key, Pairs) :-
    (   lang_lookup(Key, Pairs, V)
    ->  true
    ;   V = none
    ),
    assign_func_value(V).

% put_pair(+Key, +Value, +Pairs): Pairs with Key-Value in the place of an
% earlier pair of the same key (appended when new).
put_pair(Key, Value, Pairs) :-
    shop_put(Pairs, Key, Value, New),
    assign_func_value(New).

shop_put([], K, V, [K-V]).
shop_put([K0-V0|Ps], K, V, Out) :-
    (   K0 == K
    ->  Out = [K-V|Ps]
    ;   Out = [K0-V0|Rest],
        shop_put(Ps, K, V, Rest)
    ).

% shelf_contents(+Pairs): what the KB believes each shelf holds, from the
% Object:Shelf answers of property_extension(loc): [Shelf-[Object, ...]].
shelf_contents(Pairs) :-
    shop_contents(Pairs, [], C),
    assign_func_value(C).

shop_contents([], Acc, Acc).
shop_contents([O:S|Ps], Acc, Out) :-
    (   S == unknown
    ->  Acc1 = Acc
    ;   lang_lookup(S, Acc, Os)
    ->  lang_append(Os, [O], Os1),
        shop_put(Acc, S, Os1, Acc1)
    ;   lang_append(Acc, [S-[O]], Acc1)
    ),
    shop_contents(Ps, Acc1, Out).

% believed_on(+Shelf, +Pairs): the objects the KB places on Shelf.
believed_on(Shelf, Pairs) :-
    shop_on(Pairs, Shelf, Os),
    assign_func_value(Os).

shop_on([], _, []).
shop_on([O:S|Ps], Shelf, Out) :-
    (   S == Shelf
    ->  Out = [O|Rest]
    ;   Out = Rest
    ),
    shop_on(Ps, Shelf, Rest).

% minus(+Xs, +Ys): the Xs that are not Ys, in order.
minus(Xs, Ys) :-
    shop_minus(Xs, Ys, Zs),
    assign_func_value(Zs).

shop_minus([], _, []).
shop_minus([X|Xs], Ys, Out) :-
    (   lang_member(X, Ys)
    ->  Out = Rest
    ;   Out = [X|Rest]
    ),
    shop_minus(Xs, Ys, Rest).

% misplaced(+Objects, +Shelf, +Homes): the Objects whose right shelf (in
% Homes, Object-Shelf) is not Shelf.
misplaced(Objects, Shelf, Homes) :-
    shop_misplaced(Objects, Shelf, Homes, Ms),
    assign_func_value(Ms).

shop_misplaced([], _, _, []).
shop_misplaced([O|Os], Shelf, Homes, Out) :-
    (   lang_lookup(O, Homes, H), H \== Shelf
    ->  Out = [O|Rest]
    ;   Out = Rest
    ),
    shop_misplaced(Os, Shelf, Homes, Rest).

% add_pending(+Obligation, +Pending): Pending with a put-back obligation
% put(O, From, To), replacing an earlier one for the same object.
add_pending(put(O, From, To), Pending) :-
    shop_drop(Pending, O, P1),
    lang_append(P1, [put(O, From, To)], P2),
    assign_func_value(P2).

% drop_pending(+Object, +Pending): Pending without Object's obligation.
drop_pending(O, Pending) :-
    shop_drop(Pending, O, P),
    assign_func_value(P).

shop_drop([], _, []).
shop_drop([put(X, F, T)|Ps], O, Out) :-
    (   X == O
    ->  Out = Rest
    ;   Out = [put(X, F, T)|Rest]
    ),
    shop_drop(Ps, O, Rest).

% first_seen(+Candidates, +Observed, +Except): the first candidate seen on
% an observed shelf (Shelf-Objects pairs), not Except, or none.
first_seen(Candidates, Observed, Except) :-
    (   lang_in(C, Candidates),
        C \== Except,
        lang_in(_-Os, Observed),
        lang_member(C, Os)
    ->  true
    ;   C = none
    ),
    assign_func_value(C).

% member_of(+X, +List): yes or no.
member_of(X, List) :-
    (   lang_member(X, List)
    ->  A = yes
    ;   A = no
    ),
    assign_func_value(A).

% things(+Objects): the words "the a, the b and the c" (nothing: "nothing").
things(Objects) :-
    shop_things(Objects, Words),
    lang_words(Words, Sentence),
    assign_func_value(Sentence).

shop_things([], [nothing]).
shop_things([O], [the, O]) :- !.
shop_things([O1, O2], [the, O1, and, the, O2]) :- !.
shop_things([O|Os], [the, O, ','|Ws]) :- shop_things(Os, Ws).

% plan_words(+Plan): what the robot says it will do, from the behaviours
% of a plan (take(O, S), place(O, S), deliver(O)).
plan_words(Plan) :-
    shop_plan_words(Plan, Ws),
    lang_words(['I will' | Ws], Sentence),
    assign_func_value(Sentence).

shop_plan_words([], ['.']).
shop_plan_words([B], Ws) :- !,
    shop_step_words(B, W1),
    lang_append(W1, ['.'], Ws).
shop_plan_words([B|Bs], Ws) :-
    shop_step_words(B, W1),
    shop_plan_words(Bs, W2),
    (   W2 = [_, _|_], Bs = [_]
    ->  lang_append(W1, [', and then'|W2], Ws)
    ;   lang_append(W1, [','|W2], Ws)
    ).

shop_step_words(take(O, S), [take, the, O, from, N]) :- shop_name(S, N).
shop_step_words(place(O, S), [put, the, O, on, N]) :- shop_name(S, N).
shop_step_words(deliver(O), [bring, you, the, O]).

shop_name(S, N) :-
    (   catch(var_op(get(names, Names)), _, fail),
        lang_lookup(S, Names, N)
    ->  true
    ;   N = S
    ).

% cons(+X, +List)
cons(X, List) :-
    assign_func_value([X|List]).

% first_of(+List): the first element, or none.
first_of(List) :-
    (   List = [X|_]
    ->  true
    ;   X = none
    ),
    assign_func_value(X).

% missing(+Believed, +Seen, +Sought): what the KB placed here and is not
% seen, and the object sought if it is not seen either (the double
% exception of Section 8.1).
missing(Believed, Seen, Sought) :-
    shop_minus(Believed, Seen, M0),
    (   Sought \== none,
        \+ lang_member(Sought, Seen),
        \+ lang_member(Sought, M0)
    ->  M = [Sought|M0]
    ;   M = M0
    ),
    assign_func_value(M).

% add_pending_for(+Obligation, +Pending, +Sought): add_pending, except for
% the object being fetched for the customer.
add_pending_for(put(O, F, T), Pending, Sought) :-
    (   O == Sought
    ->  P = Pending
    ;   shop_drop(Pending, O, P1),
        lang_append(P1, [put(O, F, T)], P)
    ),
    assign_func_value(P).

% drop_steps(+Object, +Plan): the plan without the steps about Object.
drop_steps(O, Plan) :-
    shop_drop_steps(Plan, O, P),
    assign_func_value(P).

shop_drop_steps([], _, []).
shop_drop_steps([S|Ss], O, Out) :-
    (   arg(1, S, X), X == O
    ->  Out = Rest
    ;   Out = [S|Rest]
    ),
    shop_drop_steps(Ss, O, Rest).

% pending_objects(+Pending): the objects of put-back obligations.
pending_objects(Pending) :-
    shop_pending_objects(Pending, Os),
    assign_func_value(Os).

shop_pending_objects([], []).
shop_pending_objects([put(O, _, _)|Ps], [O|Os]) :- shop_pending_objects(Ps, Os).
