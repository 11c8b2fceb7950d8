% The sitlog-rs Prolog prelude: what a SitLog user function sees besides
% the application's templates.pl and user_functions.pl. Loaded into the
% embedded engine (scryer-prolog) before them. Written for sitlog-rs.
%
% One call of a user function is one query
%     '$sitlog_call'(Goal, Vars, Locals, Globals, History, Limit, Result)
% where Locals and Globals are lists Name-Value, History is the task
% history in the original's shape and Vars lists the caller's unbound
% variables (so that their bindings flow back). The environment lives in
% backtrackable global variables for the length of the call (no copies:
% a function that binds a variable inside a SitLog variable's value binds
% the caller's variable).

:- use_module(library(iso_ext)).
:- use_module(library(charsio)).

:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

% SWI-Prolog 6 idioms used by application code.
otherwise.
print(X) :- writeq(X).

% The original interpreter asserts its execution mode; applications test it
% to pick between simulated (test mode) and robot input.
:- dynamic(mode_exe/1).
mode_exe(test).

% ---------------------------------------------------------------- the call

'$sitlog_call'(Goal, Vars, Locals, Globals, History, Limit, Result) :-
    bb_b_put('$sitlog_env', env(Locals, Globals, [])),
    bb_b_put('$sitlog_history', History),
    bb_b_put('$sitlog_value', '$none'),
    catch('$sitlog_run'(Goal, Limit, R0), E, R0 = error(E)),
    '$sitlog_result'(R0, Vars, Result).

'$sitlog_run'(Goal, Limit, R) :-
    (   call_with_inference_limit(Goal, Limit, LR)
    ->  (   LR == inference_limit_exceeded
        ->  R = limit
        ;   R = done
        )
    ;   R = fail
    ).

'$sitlog_result'(done, Vars, Result) :-
    !,
    bb_get('$sitlog_value', V0),
    bb_get('$sitlog_env', env(L, G, Changed)),
    (   V0 = v(V)
    ->  '$sitlog_changes'(Changed, L, G, Changes),
        Result = ok(V, Vars, Changes)
    ;   Result = novalue
    ).
'$sitlog_result'(R, _, R).

'$sitlog_changes'([], _, _, []).
'$sitlog_changes'([W-N|Ns], L, G, [C|Cs]) :-
    (   W == l
    ->  '$sitlog_memberchk'(N-V, L),
        C = l(N, V)
    ;   '$sitlog_memberchk'(N-V, G),
        C = g(N, V)
    ),
    '$sitlog_changes'(Ns, L, G, Cs).

% -------------------------------------------------- what functions call

% assign_func_value(V): the value of the function (the last call wins).
assign_func_value(V) :-
    bb_b_put('$sitlog_value', v(V)).

% get_history(H): the task history as it stands (read only).
get_history(H) :-
    bb_get('$sitlog_history', H).

% var_op(Op): get/set/inc of a local (first) or global SitLog variable,
% with the semantics of the L evaluator; a list of operations is done in
% order.
var_op(Op) :-
    var(Op),
    !,
    throw(error(instantiation_error, var_op/1)).
var_op([]) :- !.
var_op([Op|Ops]) :- !, var_op(Op), var_op(Ops).
var_op(get(N, V)) :- !,
    '$sitlog_lookup'(N, _, Value),
    V = Value.
var_op(set(N, V)) :- !,
    '$sitlog_lookup'(N, Where, _),
    '$sitlog_update'(Where, N, V).
var_op(inc(N, V)) :- !,
    '$sitlog_lookup'(N, Where, Old),
    (   number(Old)
    ->  New is Old + 1
    ;   throw(error(type_error(number, Old), var_op(inc(N, V))))
    ),
    '$sitlog_update'(Where, N, New),
    V = New.
var_op(Op) :-
    throw(error(domain_error(sitlog_var_op, Op), var_op/1)).

'$sitlog_lookup'(N, Where, Value) :-
    (   atom(N)
    ->  true
    ;   throw(error(type_error(atom, N), var_op/1))
    ),
    bb_get('$sitlog_env', env(L, G, _)),
    (   '$sitlog_memberchk'(N-V0, L)
    ->  Where = l
    ;   '$sitlog_memberchk'(N-V0, G)
    ->  Where = g
    ;   throw(error(existence_error(sitlog_variable, N), var_op/1))
    ),
    Value = V0.

'$sitlog_update'(Where, N, V) :-
    bb_get('$sitlog_env', env(L0, G0, C0)),
    (   Where == l
    ->  '$sitlog_replace'(L0, N, V, L), G = G0
    ;   '$sitlog_replace'(G0, N, V, G), L = L0
    ),
    (   '$sitlog_memberchk'(Where-N, C0)
    ->  C = C0
    ;   C = [Where-N|C0]
    ),
    bb_b_put('$sitlog_env', env(L, G, C)).

'$sitlog_replace'([], _, _, []).
'$sitlog_replace'([K-V0|KVs], N, V, [K-V1|Rest]) :-
    (   K == N
    ->  V1 = V,
        Rest = KVs
    ;   V1 = V0,
        '$sitlog_replace'(KVs, N, V, Rest)
    ).

% ---------------------------------------------- the original's helpers

% get_current_DM(History, Entries): the entries of the current DM level,
% in order: those after the last nested (embedded DM) history.
get_current_DM(History, Entries) :-
    '$sitlog_current'(History, [], Rev),
    '$sitlog_reverse'(Rev, [], Entries).

'$sitlog_current'([], Acc, Acc).
'$sitlog_current'([H|T], Acc, Out) :-
    (   '$sitlog_is_list'(H)
    ->  '$sitlog_current'(T, [], Out)
    ;   '$sitlog_current'(T, [H|Acc], Out)
    ).

'$sitlog_is_list'(X) :- X == [], !.
'$sitlog_is_list'([_|_]).

'$sitlog_reverse'([], Acc, Acc).
'$sitlog_reverse'([X|Xs], Acc, R) :- '$sitlog_reverse'(Xs, [X|Acc], R).

% get_last_transition(History, Expectation:Action): of the last entry of
% the current DM level; `none` for an empty history.
get_last_transition([], none) :- !.
get_last_transition(History, E:A) :-
    get_current_DM(History, Entries),
    '$sitlog_reverse'(Entries, [], [_:(_, E:A)|_]).

% get_last_situation(History, Situation): the situation of that entry.
get_last_situation([], none) :- !.
get_last_situation(History, S) :-
    get_current_DM(History, Entries),
    '$sitlog_reverse'(Entries, [], [_:(S, _)|_]).

% ------------------------------------------------------------- loading

'$sitlog_add'(Clause, R) :-
    catch((assertz(Clause), R = ok), E, R = error(E)).

'$sitlog_directive'(Goal, R) :-
    catch(( call(Goal) -> R = ok ; R = fail ), E, R = error(E)).

% Imports a library's predicates except those the application defines
% (SWI-Prolog's autoloading gives user definitions precedence).
'$sitlog_import'(Library, Preds, R) :-
    '$sitlog_exclude_defined'(Preds, Keep),
    catch((use_module(library(Library), Keep), R = ok), E, R = error(E)).

'$sitlog_exclude_defined'([], []).
'$sitlog_exclude_defined'([N/A|Ps], Keep) :-
    (   functor(H, N, A),
        catch(predicate_property(H, dynamic), _, fail)
    ->  Keep = Keep1
    ;   Keep = [N/A|Keep1]
    ),
    '$sitlog_exclude_defined'(Ps, Keep1).

'$sitlog_memberchk'(X, [Y|Ys]) :-
    (   X = Y
    ->  true
    ;   '$sitlog_memberchk'(X, Ys)
    ).
