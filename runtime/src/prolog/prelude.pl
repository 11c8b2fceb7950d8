% The sitlog-rs Prolog prelude: what a SitLog user function sees besides
% the application's templates.pl and user_functions.pl. Loaded into the
% embedded engine (scryer-prolog) before them. Written for sitlog-rs.
%
% One call of a user function is one query
%     '$sitlog_call'(Goal, Vars, Locals, Globals, Limit, Result)
% where Locals and Globals are lists Name-Value and Vars lists the
% caller's unbound variables (so that their bindings flow back). The task
% history is not sent with the call: get_history/1 asks the host for it,
% in parts, when a function reads it. The environment lives in
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

'$sitlog_call'(Goal, Vars, Locals, Globals, Limit, Result) :-
    bb_b_put('$sitlog_env', env(Locals, Globals, [])),
    bb_b_put('$sitlog_history', '$ask'),
    bb_b_put('$sitlog_value', '$none'),
    catch('$sitlog_run'(Goal, Limit, R0), E, R0 = error(E)),
    '$sitlog_result'(R0, Vars, Result0),
    '$sitlog_safe'(Result0, Result).

% '$sitlog_safe'(Answer0, Answer): an answer the engine can hand over.
% Its conversion of an answer cannot take a list whose tail is an atom
% other than [] ([a|b]; [a|f(x)] and [a|_] it takes) nor a cyclic term:
% such an answer becomes improper(Text), the value (or the whole answer)
% written out, or `cyclic`, each an error of the call naming it. The
% answer is walked once, not copied, up to 20 000 nodes (a cyclic
% term has more); acyclic_term/1 only past them (it spoils a partial
% string's atom tail, so it is not asked first). The value is written to a
% depth of 24 (a long list's elements past it as `...`: writing all of a
% list of thousands of one-character atoms took longer than a call may).
'$sitlog_safe'(T0, T) :-
    '$sitlog_scan'(T0, 20000, _, R),
    (   R == found
    ->  (   T0 = ok(V, _, _), '$sitlog_scan'(V, 20000, _, found)
        ->  W = V
        ;   W = T0
        ),
        (   catch(write_term_to_chars(W, [quoted(true), max_depth(24)], Cs), _, fail)
        ->  atom_chars(Text, Cs)
        ;   Text = '?'
        ),
        T = improper(Text)
    ;   R == out, \+ acyclic_term(T0)
    ->  T = cyclic
    ;   T = T0
    ).

% '$sitlog_scan'(T, Budget0, Budget, R): R is found (a list with an atom
% tail in T), none, or out (Budget0 nodes walked, not done).
'$sitlog_scan'(T, B0, B, R) :-
    (   B0 =< 0
    ->  B = B0,
        R = out
    ;   \+ compound(T)
    ->  B is B0 - 1,
        R = none
    ;   T = [H|Tl]
    ->  B1 is B0 - 1,
        '$sitlog_scan'(H, B1, B2, R1),
        (   R1 \== none
        ->  B = B2,
            R = R1
        ;   atom(Tl), Tl \== []
        ->  B = B2,
            R = found
        ;   '$sitlog_scan'(Tl, B2, B, R)
        )
    ;   functor(T, _, N),
        B1 is B0 - 1,
        '$sitlog_scan_args'(1, N, T, B1, B, R)
    ).

'$sitlog_scan_args'(I, N, T, B0, B, R) :-
    (   I > N
    ->  B = B0,
        R = none
    ;   arg(I, T, A),
        '$sitlog_scan'(A, B0, B1, R1),
        (   R1 \== none
        ->  B = B1,
            R = R1
        ;   I1 is I + 1,
            '$sitlog_scan_args'(I1, N, T, B1, B, R)
        )
    ).

'$sitlog_run'(Goal, inf, R) :-
    !,
    (   call(Goal)
    ->  R = done
    ;   R = fail
    ).
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

% get_history(H): the task history as it stands (read only), asked of the
% host at the first call of the function's query and kept for the rest of
% it.
get_history(H) :-
    bb_get('$sitlog_history', H0),
    (   H0 = h(H1)
    ->  true
    ;   '$sitlog_history_from'(0, H1),
        bb_b_put('$sitlog_history', h(H1))
    ),
    H = H1.

% A request to the host whose answer may be long: Tag and Arg framed by
% \x1\ and \x2\ on user_error; the host answers a line with the answer's
% length in characters, then the answer (read in one go:
% get_line_to_chars/3 reads a character at a time).
'$sitlog_ask_long'(Tag, Arg, Reply) :-
    put_char(user_error, '\x1\'),
    put_char(user_error, Tag),
    write(user_error, Arg),
    put_char(user_error, '\x2\'),
    flush_output(user_error),
    '$sitlog_read_long'(Reply).

% A long answer of the host: its length, then the answer in one read.
'$sitlog_read_long'(Reply) :-
    get_line_to_chars(user_input, Line, []),
    '$sitlog_history_append'(Digits, ['\n'], Line),
    number_chars(Length, Digits),
    get_n_chars(user_input, Length, Text),
    read_from_chars(Text, Reply).

% The history from element From on: the host answers a part of it at a
% time, '$ok'(Elements, Next) with Next the next part's index or `end`
% (engine.rs, history_part).
'$sitlog_history_from'(From, H) :-
    '$sitlog_ask_long'('H', From, Reply),
    (   Reply = '$ok'(Part, Next)
    ->  true
    ;   Reply = '$error'(E)
    ->  throw(E)
    ),
    '$sitlog_history_join'(Part, Tail, H),
    (   Next == end
    ->  Tail = []
    ;   '$sitlog_history_from'(Next, Tail)
    ).

'$sitlog_history_append'([], L, L).
'$sitlog_history_append'([X|Xs], L, [X|Ys]) :- '$sitlog_history_append'(Xs, L, Ys).

'$sitlog_history_join'([], T, T).
'$sitlog_history_join'([X|Xs], T, [X|Ys]) :- '$sitlog_history_join'(Xs, T, Ys).

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

% Asserts the clauses that are the arguments of Cs (`c(C1, ..., Cn)`: two
% levels above a clause, where a list would add one per element), in order;
% R: `K-E` for each clause Ck refused with the error E.
'$sitlog_add_all'(Cs, R) :-
    functor(Cs, _, N),
    '$sitlog_add_all'(1, N, Cs, R).
'$sitlog_add_all'(K, N, Cs, R) :-
    (   K > N
    ->  R = []
    ;   arg(K, Cs, C),
        catch((assertz(C), R = R1), E, R = [K-E|R1]),
        K1 is K + 1,
        '$sitlog_add_all'(K1, N, Cs, R1)
    ).

% A predicate of the legacy layer loaded at its first call (engine.rs,
% lazify): its stub clause `P(V..) :- '$sitlog_lazy'(Id, N, A), P(V..)`
% goes, and its clauses, asked of the host (a line with the answer's
% length, then '$ok'([c(C1, ..), ..]) or '$static'([c(C1, ..), ..])), are
% asserted ('$ok') or compiled as a consulted file's predicate would be
% ('$static': the engine runs a static predicate without looking for the
% next clause alive at each try, as it must for a dynamic one). Tag `L`
% lets the host answer either; `M` (a call that changes or looks at the
% predicate's clauses loads it) asks for '$ok'. Nothing when the stub is
% gone (loaded already, or redefined by a later file).
:- dynamic('$sitlog_static'/3).
'$sitlog_lazy'(Id, N, A) :-
    '$sitlog_lazy'(Id, N, A, 'L').
'$sitlog_lazy'(Id, N, A, Tag) :-
    functor(H, N, A),
    (   retract((H :- '$sitlog_lazy'(Id, _, _), _))
    ->  '$sitlog_ask_long'(Tag, Id, Reply),
        (   Reply = '$ok'(Groups)
        ->  '$sitlog_lazy_add'(Groups)
        ;   Reply = '$static'(Groups)
        ->  '$sitlog_static_add'(N, A, Groups),
            assertz('$sitlog_static'(N, A, Id))
        ;   throw(error(existence_error(procedure, N/A), '$sitlog_lazy'/3))
        )
    ;   true
    ).

% The clauses of N/A (no clause left: its stub was retracted) compiled as
% the engine's loader compiles a consulted file's (`load/1`, from terms
% rather than a stream).
'$sitlog_static_add'(N, A, Groups) :-
    abolish(N/A),
    '$sitlog_compile'([], Groups).

% A predicate loaded static whose clauses a call is about to change or
% look at becomes dynamic with the same clauses, asked of the host again
% (a `C` request): loaded again, declared dynamic (SWI-Prolog's, and so
% the original's, are all open to the layer's assert/retract/clause).
'$sitlog_unstatic'(N, A, Id) :-
    retract('$sitlog_static'(N, A, Id)),
    '$sitlog_ask_long'('C', Id, Reply),
    (   Reply = '$ok'(Groups)
    ->  '$sitlog_compile'([(:- dynamic(N/A))], Groups)
    ;   throw(error(existence_error(procedure, N/A), '$sitlog_unstatic'/3))
    ).

% Terms, then the clauses of Groups, compiled in a load context of their
% own, as `load/1` does.
'$sitlog_compile'(Terms, Groups) :-
    (   current_input(S),
        loader:create_load_context(S, Ev),
        catch('$sitlog_compile_do'(Terms, Groups, Ev), E,
              ( loader:unload_evacuable(Ev), throw(E) )),
        '$pop_load_context',
        false                           % the load's terms off the heap
    ;   true
    ).
% ('$conclude_load'/1 is an instruction of the engine, not a predicate:
% called directly, never through call/N.)
'$sitlog_compile_do'(Terms, Groups, Ev) :-
    '$sitlog_compile_list'(Terms, Ev),
    '$sitlog_compile_groups'(Groups, Ev),
    '$conclude_load'(Ev).
'$sitlog_compile_list'([], _).
'$sitlog_compile_list'([T|Ts], Ev) :-
    loader:compile_term(T, Ev),
    '$sitlog_compile_list'(Ts, Ev).
'$sitlog_compile_groups'([], _).
'$sitlog_compile_groups'([Cs|Gs], Ev) :-
    functor(Cs, _, K),
    '$sitlog_compile_each'(1, K, Cs, Ev),
    '$sitlog_compile_groups'(Gs, Ev).
% A clause of the predicate goes to the load directly, as assertz/1
% compiles one (no term or goal expansion: the loader's own, per body goal,
% was most of a load's cost); a module-qualified one through the loader.
'$sitlog_compile_each'(I, K, Cs, Ev) :-
    (   I > K
    ->  true
    ;   arg(I, Cs, C),
        (   ( C = (_:_) ; C = (_:_ :- _) )
        ->  loader:compile_term(C, Ev)
        ;   '$clause_to_evacuable'(C, Ev)
        ),
        I1 is I + 1,
        '$sitlog_compile_each'(I1, K, Cs, Ev)
    ).

% The stubs of waiting predicates (engine.rs, add_stubs), from
% s(N, A, Id) each, in order; R as for '$sitlog_add_all'/2.
'$sitlog_stubs'(Ss, R) :-
    '$sitlog_stubs'(Ss, 1, R).
'$sitlog_stubs'([], _, []).
'$sitlog_stubs'([s(N, A, Id)|Ss], K, R) :-
    functor(H, N, A),
    catch((assertz((H :- '$sitlog_lazy'(Id, N, A), H)), R = R1), E, R = [K-E|R1]),
    K1 is K + 1,
    '$sitlog_stubs'(Ss, K1, R1).

'$sitlog_lazy_add'([]).
'$sitlog_lazy_add'([Cs|Gs]) :-
    '$sitlog_add_all'(Cs, R),
    (   R = [_-E|_] -> throw(E) ; true ),
    '$sitlog_lazy_add'(Gs).

% The calls that change or look at a predicate's clauses, as the legacy
% layer's and the application's clauses call them (translate.rs,
% TOUCHING): a predicate still waiting for its first call is loaded first.
'$sitlog_lz_assert'(C) :-
    '$sitlog_lz_clause_touch'(C), '$sitlog_lz_undirect'(C),
    '$sitlog_kb_rule'(C, C1), assertz(C1).
'$sitlog_lz_asserta'(C) :-
    '$sitlog_lz_clause_touch'(C), '$sitlog_lz_undirect'(C),
    '$sitlog_kb_rule'(C, C1), asserta(C1).
'$sitlog_lz_assertz'(C) :-
    '$sitlog_lz_clause_touch'(C), '$sitlog_lz_undirect'(C),
    '$sitlog_kb_rule'(C, C1), assertz(C1).

% A wrapped predicate of the native KB layer whose clauses call their own
% ('$legacy_P') directly (legacy_kb.rs, direct_recursion; a fact
% '$sitlog_direct'(P, A, K) each): a clause asserted for P at run time
% would not be seen by those calls, so '$legacy_P' gets its clauses as
% written back from the host (a D request), calling P by name.
:- dynamic('$sitlog_direct'/3).
'$sitlog_lz_undirect'(C) :-
    (   '$sitlog_direct'(_, _, _),
        nonvar(C),
        ( C = (_:C2) -> true ; C2 = C ),
        nonvar(C2),
        ( C2 = (H :- _) -> true ; H = C2 ),
        callable(H),
        functor(H, N, A),
        retract('$sitlog_direct'(N, A, K))
    ->  '$sitlog_ask_long'('D', K, Reply),
        (   Reply = '$ok'(Gs), Gs \== []
        ->  atom_concat('$legacy_', N, L),
            functor(G, L, A),
            '$sitlog_lz_touch'(L, A),
            retractall(G),
            '$sitlog_lazy_add'(Gs)
        ;   Reply = '$ok'(_)
        ->  true
        ;   Reply = '$error'(E)
        ->  throw(E)
        ;   throw(error(existence_error(procedure, N/A), '$sitlog_lz_undirect'/1))
        )
    ;   true
    ).
'$sitlog_lz_retract'(C) :- '$sitlog_lz_clause_touch'(C), retract(C).
'$sitlog_lz_retractall'(H) :- '$sitlog_lz_touch'(H), retractall(H).
'$sitlog_lz_abolish'(PI) :-
    (   nonvar(PI), PI = N/A -> '$sitlog_lz_touch'(N, A)
    ;   nonvar(PI), PI = _:(N/A) -> '$sitlog_lz_touch'(N, A)
    ;   true
    ),
    abolish(PI).
'$sitlog_lz_abolish'(N, A) :- '$sitlog_lz_touch'(N, A), abolish(N/A).
'$sitlog_lz_clause'(H, B) :- '$sitlog_lz_touch'(H), clause(H, B).

'$sitlog_lz_clause_touch'(C) :-
    (   nonvar(C), C = (_:C1) -> '$sitlog_lz_clause_touch'(C1)
    ;   nonvar(C), C = (H :- _) -> '$sitlog_lz_touch'(H)
    ;   '$sitlog_lz_touch'(C)
    ).
'$sitlog_lz_touch'(H) :-
    (   nonvar(H), H = (_:H1) -> '$sitlog_lz_touch'(H1)
    ;   callable(H) -> functor(H, N, A), '$sitlog_lz_touch'(N, A)
    ;   true
    ).
% The stub, if it is there, is the predicate's only clause; a predicate
% loaded static becomes dynamic.
'$sitlog_lz_touch'(N, A) :-
    (   atom(N), integer(A), A >= 0,
        functor(G, N, A),
        catch(once(clause(G, B)), _, fail),
        nonvar(B), B = ('$sitlog_lazy'(Id, _, _), _)
    ->  '$sitlog_lazy'(Id, N, A, 'M')
    ;   atom(N), '$sitlog_static'(N, A, Id)
    ->  '$sitlog_unstatic'(N, A, Id)
    ;   true
    ).

% A clause asserted ahead (the legacy layer, by an engine built ahead) of
% a predicate that a later file redefines: the predicate's clauses go.
'$sitlog_drop'(Clause, R) :-
    (   Clause = (H :- _) -> true ; H = Clause ),
    functor(H, N, A),
    functor(G, N, A),
    catch((retractall(G), R = ok), E, R = error(E)).

'$sitlog_directive'(Goal, R) :-
    catch(( call(Goal) -> R = ok ; R = fail ), E, R = error(E)).

% An application's directive, under the run's inference limit.
'$sitlog_directive'(Goal, Limit, R) :-
    catch('$sitlog_run'(Goal, Limit, R0), E, R0 = error(E)),
    (   R0 == done
    ->  R = ok
    ;   R0 == limit
    ->  R = limit(Limit)
    ;   R = R0
    ).

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

% ------------------------------------------- SWI-Prolog compatibility
% Programs written for the original run on SWI-Prolog and call its
% built-ins and autoloaded library predicates. Each '$swi_X' below is made
% visible as X once the application's clauses are loaded, unless the
% application defines X itself or the engine already has it
% ('$sitlog_bridge'/2, list in swi.rs). Built-ins the engine has but
% with another behaviour (atom_chars/2 on codes, the standard order of
% mixed integers and floats, reading text) cannot be redefined: the
% application's clauses call the '$swi_X' versions instead (the loader
% renames those calls, see swi.rs).

:- dynamic('$sitlog_env'/2).
:- use_module(library(os), []).
:- use_module(library(random), [random/1]).

'$sitlog_length'(L, N) :- '$sitlog_length'(L, 0, N).
'$sitlog_length'(L, N0, N) :-
    (   L == [] -> N = N0
    ;   nonvar(L), L = [_|T] -> N1 is N0 + 1, '$sitlog_length'(T, N1, N)
    ;   throw(error(type_error(list, L), length/2))
    ).
'$sitlog_split_at'(0, L, [], L) :- !.
'$sitlog_split_at'(N, [X|Xs], [X|As], B) :- N1 is N - 1, '$sitlog_split_at'(N1, Xs, As, B).

'$sitlog_append'([], L, L).
'$sitlog_append'([X|Xs], L, [X|Ys]) :- '$sitlog_append'(Xs, L, Ys).

% getenv(+Name, -Value): the host's environment, atoms (SWI).
'$swi_getenv'(Name, Value) :-
    '$swi_text_chars'(Name, Cs),
    atom_chars(N, Cs),
    (   '$sitlog_env'(N, V0)
    ->  Value = V0
    ;   catch(os:getenv(Cs, VCs), _, fail),
        atom_chars(Value, VCs)
    ).

% Text of an atom, number, code list or char list, as chars.
'$swi_text_chars'(X, Cs) :-
    (   var(X)
    ->  throw(error(instantiation_error, text/1))
    ;   atom(X)
    ->  atom_chars(X, Cs)
    ;   number(X)
    ->  number_chars(X, Cs)
    ;   X == []
    ->  Cs = []
    ;   X = [C|_], integer(C)
    ->  (   catch(atom_codes(A, X), _, fail)   % the engine's, in one call
        ->  atom_chars(A, Cs)
        ;   '$swi_codes_chars'(X, Cs)
        )
    ;   X = [_|_]
    ->  Cs = X
    ;   throw(error(type_error(atomic, X), text/1))
    ).

'$swi_codes_chars'([], []).
'$swi_codes_chars'([C|Cs], [H|Hs]) :- char_code(H, C), '$swi_codes_chars'(Cs, Hs).

% atomic_concat(+A, +B, -Atom) (SWI-Prolog 5 and earlier).
'$swi_atomic_concat'(A, B, C) :-
    '$swi_text_chars'(A, As),
    '$swi_text_chars'(B, Bs),
    '$sitlog_append'(As, Bs, Cs),
    atom_chars(C, Cs).

% get0(-Code), get0(+Stream, -Code): -1 at the end.
'$swi_get0'(C) :- get_code(C).
'$swi_get0'(S, C) :- get_code(S, C).

% atom_chars(?Atom, ?Text): SWI accepts a code list for Text.
'$swi_atom_chars'(A, L) :-
    (   var(A), nonvar(L), L = [C|_], integer(C)
    ->  atom_codes(A, L)
    ;   atom_chars(A, L)
    ).

% atom_to_chars(+Atom, -Codes) (library(charsio) of SWI).
'$swi_atom_to_chars'(A, Codes) :-
    (   atom(A)
    ->  atom_codes(A, Codes)
    ;   '$swi_text_chars'(A, Cs),
        '$swi_chars_codes'(Cs, Codes)
    ).

'$swi_chars_codes'([], []).
'$swi_chars_codes'([C|Cs], [H|Hs]) :- char_code(C, H), '$swi_chars_codes'(Cs, Hs).

% flatten(+List, -Flat).
'$swi_flatten'(List, Flat) :-
    '$swi_flatten'(List, [], Flat0),
    !,
    Flat = Flat0.
'$swi_flatten'(Var, Tl, [Var|Tl]) :- var(Var), !.
'$swi_flatten'([], Tl, Tl) :- !.
'$swi_flatten'([Hd|Tl], Tail, List) :- !,
    '$swi_flatten'(Hd, FlatHeadTail, List),
    '$swi_flatten'(Tl, Tail, FlatHeadTail).
'$swi_flatten'(NonList, Tl, [NonList|Tl]).

% assert/1 is assertz/1.
'$swi_assert'(C) :- assertz(C).

% random_permutation(+List, -Permutation).
'$swi_random_permutation'(List, Perm) :-
    '$swi_keyed_random'(List, Keyed),
    keysort(Keyed, Sorted),
    '$swi_values'(Sorted, Perm).

'$swi_keyed_random'([], []).
'$swi_keyed_random'([X|Xs], [K-X|Ks]) :- random(K), '$swi_keyed_random'(Xs, Ks).

'$swi_values'([], []).
'$swi_values'([_-V|Ps], [V|Vs]) :- '$swi_values'(Ps, Vs).

% last(?List, ?Last).
'$swi_last'([X|Xs], Last) :- '$swi_last_'(Xs, X, Last).
'$swi_last_'([], Last, Last).
'$swi_last_'([X|Xs], _, Last) :- '$swi_last_'(Xs, X, Last).

% include/3, exclude/3, partition/4 (library(apply)).
'$swi_include'(_, [], []).
'$swi_include'(P, [X|Xs], L) :-
    (   call(P, X) -> L = [X|L1] ; L = L1 ),
    '$swi_include'(P, Xs, L1).
'$swi_exclude'(_, [], []).
'$swi_exclude'(P, [X|Xs], L) :-
    (   call(P, X) -> L = L1 ; L = [X|L1] ),
    '$swi_exclude'(P, Xs, L1).
'$swi_partition'(_, [], [], []).
'$swi_partition'(P, [X|Xs], I, E) :-
    (   call(P, X) -> I = [X|I1], E = E1 ; I = I1, E = [X|E1] ),
    '$swi_partition'(P, Xs, I1, E1).

% Other library(lists) predicates of SWI.
'$swi_sumlist'(L, S) :- '$swi_sum'(L, 0, S).
'$swi_sum'([], S, S).
'$swi_sum'([X|Xs], S0, S) :- S1 is S0 + X, '$swi_sum'(Xs, S1, S).
'$swi_max_list'([X|Xs], M) :- '$swi_max_list_'(Xs, X, M).
'$swi_max_list_'([], M, M).
'$swi_max_list_'([X|Xs], M0, M) :- M1 is max(M0, X), '$swi_max_list_'(Xs, M1, M).
'$swi_min_list'([X|Xs], M) :- '$swi_min_list_'(Xs, X, M).
'$swi_min_list_'([], M, M).
'$swi_min_list_'([X|Xs], M0, M) :- M1 is min(M0, X), '$swi_min_list_'(Xs, M1, M).
'$swi_delete'([], _, []).
'$swi_delete'([X|Xs], D, R) :-
    (   X \= D -> R = [X|R1] ; R = R1 ),
    '$swi_delete'(Xs, D, R1).
'$swi_subtract'([], _, []).
'$swi_subtract'([X|Xs], L, R) :-
    (   '$sitlog_memberchk'(X, L) -> R = R1 ; R = [X|R1] ),
    '$swi_subtract'(Xs, L, R1).
'$swi_intersection'([], _, []).
'$swi_intersection'([X|Xs], L, R) :-
    (   '$sitlog_memberchk'(X, L) -> R = [X|R1] ; R = R1 ),
    '$swi_intersection'(Xs, L, R1).
'$swi_union'([], L, L).
'$swi_union'([X|Xs], L, R) :-
    (   '$sitlog_memberchk'(X, L) -> R = R1 ; R = [X|R1] ),
    '$swi_union'(Xs, L, R1).
'$swi_sum_list'(L, S) :- '$swi_sumlist'(L, S).
'$swi_max_member'(M, L) :- '$swi_msort'(L, S), '$swi_last'(S, M).
'$swi_min_member'(M, [X|Xs]) :- '$swi_msort'([X|Xs], [M|_]).

% atomic_list_concat/2, /3 (the /3 form also splits), concat_atom.
'$swi_atomic_list_concat'(L, A) :-
    '$swi_concat_all'(L, Cs),
    atom_chars(A, Cs).
'$swi_atomic_list_concat'(L, Sep, A) :-
    (   '$swi_ground_list'(L)
    ->  '$swi_text_chars'(Sep, SCs),
        '$swi_join'(L, SCs, Cs),
        atom_chars(A, Cs)
    ;   '$swi_text_chars'(Sep, SCs), SCs \== [],
        '$swi_text_chars'(A, ACs),
        '$swi_split'(ACs, SCs, Parts),
        '$swi_atoms'(Parts, L)
    ).
'$swi_concat_atom'(L, A) :- '$swi_atomic_list_concat'(L, A).
'$swi_concat_atom'(L, S, A) :- '$swi_atomic_list_concat'(L, S, A).

'$swi_ground_list'(L) :- ground(L), catch('$sitlog_length'(L, _), _, fail).
'$swi_concat_all'([], []).
'$swi_concat_all'([X|Xs], Cs) :-
    '$swi_text_chars'(X, C0), '$swi_concat_all'(Xs, C1), '$sitlog_append'(C0, C1, Cs).
'$swi_join'([], _, []).
'$swi_join'([X], _, Cs) :- !, '$swi_text_chars'(X, Cs).
'$swi_join'([X|Xs], Sep, Cs) :-
    '$swi_text_chars'(X, C0), '$swi_join'(Xs, Sep, C1),
    '$sitlog_append'(Sep, C1, C2), '$sitlog_append'(C0, C2, Cs).
'$swi_split'(Cs, Sep, [P|Ps]) :-
    (   '$sitlog_append'(P, Rest, Cs), '$sitlog_append'(Sep, After, Rest)
    ->  '$swi_split'(After, Sep, Ps)
    ;   P = Cs, Ps = []
    ).
'$swi_atoms'([], []).
'$swi_atoms'([Cs|Css], [A|As]) :- atom_chars(A, Cs), '$swi_atoms'(Css, As).

% atom_number(+Atom, -Number): fails if Atom does not read as a number.
'$swi_atom_number'(A, N) :-
    (   atom(A)
    ->  atom_chars(A, Cs), catch(number_chars(N0, Cs), _, fail), N = N0
    ;   number(N), number_chars(N, Cs), atom_chars(A, Cs)
    ).

% upcase_atom/2, downcase_atom/2.
'$swi_upcase_atom'(A, U) :-
    '$swi_text_chars'(A, Cs), '$swi_map_case'(Cs, upper, Us), atom_chars(U, Us).
'$swi_downcase_atom'(A, U) :-
    '$swi_text_chars'(A, Cs), '$swi_map_case'(Cs, lower, Us), atom_chars(U, Us).
'$swi_map_case'([], _, []).
'$swi_map_case'([C|Cs], Case, [D|Ds]) :-
    char_code(C, X),
    (   Case == upper, X >= 0'a, X =< 0'z -> Y is X - 32, char_code(D, Y)
    ;   Case == lower, X >= 0'A, X =< 0'Z -> Y is X + 32, char_code(D, Y)
    ;   D = C
    ),
    '$swi_map_case'(Cs, Case, Ds).

% nb_getval/2, nb_setval/2, b_getval/2, b_setval/2 (global variables).
'$swi_nb_setval'(K, V) :- bb_put(K, V).
'$swi_nb_getval'(K, V) :- bb_get(K, V).
'$swi_b_setval'(K, V) :- bb_b_put(K, V).
'$swi_b_getval'(K, V) :- bb_get(K, V).

% ------------------------------------------ SWI's standard order of terms
% SWI-Prolog compares numbers by value (1 < 1.5 < 2); equal values order a
% float before an integer. The engine orders every float before every
% integer (ISO). The application's compare/3, @</2 ... sort/2, msort/2,
% sort/4, keysort/2 are these.

'$swi_compare'(O, A, B) :-
    (   number(A), number(B)
    ->  (   A < B -> O = (<)
        ;   A > B -> O = (>)
        ;   compare(O, A, B)      % equal value: float before integer
        )
    ;   compound(A), compound(B),
        functor(A, N, Ar), functor(B, N, Ar)
    ->  '$swi_compare_args'(1, Ar, A, B, O)
    ;   compare(O, A, B)
    ).

'$swi_compare_args'(I, Ar, A, B, O) :-
    (   I > Ar
    ->  O = (=)
    ;   arg(I, A, X), arg(I, B, Y),
        '$swi_compare'(O1, X, Y),
        (   O1 == (=)
        ->  I1 is I + 1,
            '$swi_compare_args'(I1, Ar, A, B, O)
        ;   O = O1
        )
    ).

'$swi_@<'(A, B) :- '$swi_compare'(<, A, B).
'$swi_@>'(A, B) :- '$swi_compare'(>, A, B).
'$swi_@=<'(A, B) :- '$swi_compare'(O, A, B), O \== (>).
'$swi_@>='(A, B) :- '$swi_compare'(O, A, B), O \== (<).

% Whether a term has both an integer and a float in it (else the engine's
% own order is SWI's and its sorts are used).
'$swi_mixed'(T) :- '$swi_kinds'(T, n, K), K == both.
'$swi_kinds'(T, K0, K) :-
    (   K0 == both -> K = both
    ;   var(T) -> K = K0
    ;   integer(T) -> ( K0 == f -> K = both ; K = i )
    ;   float(T) -> ( K0 == i -> K = both ; K = f )
    ;   compound(T) -> functor(T, _, N), '$swi_kinds_args'(1, N, T, K0, K)
    ;   K = K0
    ).
'$swi_kinds_args'(I, N, T, K0, K) :-
    (   I > N -> K = K0
    ;   arg(I, T, A), '$swi_kinds'(A, K0, K1), I1 is I + 1,
        '$swi_kinds_args'(I1, N, T, K1, K)
    ).

'$swi_msort'(L, S) :-
    (   '$swi_mixed'(L)
    ->  '$swi_merge_sort'(L, key0, (=<), S)
    ;   '$swi_self_keyed'(L, P), keysort(P, SP), '$swi_values'(SP, S)
    ).
'$swi_self_keyed'([], []).
'$swi_self_keyed'([X|Xs], [X-X|Ps]) :- '$swi_self_keyed'(Xs, Ps).
'$swi_sort'(L, S) :-
    (   '$swi_mixed'(L)
    ->  '$swi_merge_sort'(L, key0, (<), S)
    ;   sort(L, S)
    ).
'$swi_keysort'(L, S) :-
    (   '$swi_mixed'(L)
    ->  '$swi_merge_sort'(L, pair, (=<), S)
    ;   keysort(L, S)
    ).
% sort(+Key, +Order, +List, -Sorted): Key 0 is the whole term; Order one
% of @<, @=<, @>, @>= (@< and @> remove duplicates).
'$swi_sort'(Key, Order, L, S) :-
    (   Order == (@<) -> O = (<)
    ;   Order == (@=<) -> O = (=<)
    ;   Order == (@>) -> O = (>)
    ;   Order == (@>=) -> O = (>=)
    ;   throw(error(domain_error(order, Order), sort/4))
    ),
    ( Key == 0 -> K = key0 ; K = arg(Key) ),
    '$swi_merge_sort'(L, K, O, S).

% predsort(+Pred, +List, -Sorted): Pred's order; elements it finds = are
% dropped.
'$swi_predsort'(P, L, Sorted) :-
    '$sitlog_length'(L, N),
    (   N =< 1 -> Sorted = L
    ;   H is N // 2, '$sitlog_split_at'(H, L, A, B),
        '$swi_predsort'(P, A, SA),
        '$swi_predsort'(P, B, SB),
        '$swi_predmerge'(SA, SB, P, Sorted)
    ).
'$swi_predmerge'([], L, _, L) :- !.
'$swi_predmerge'(L, [], _, L) :- !.
'$swi_predmerge'([X|Xs], [Y|Ys], P, S) :-
    call(P, O, X, Y),
    (   O == (<) -> S = [X|S1], '$swi_predmerge'(Xs, [Y|Ys], P, S1)
    ;   O == (>) -> S = [Y|S1], '$swi_predmerge'([X|Xs], Ys, P, S1)
    ;   O == (=) -> S = [X|S1], '$swi_predmerge'(Xs, Ys, P, S1)
    ;   throw(error(domain_error(order, O), predsort/3))
    ).

'$swi_key'(key0, X, X).
'$swi_key'(pair, K-_, K).
'$swi_key'(arg(I), X, K) :- arg(I, X, K).

% A stable merge sort; Order < and > drop elements equal to the one kept.
'$swi_merge_sort'(L, Key, Order, S) :-
    '$sitlog_length'(L, N),
    (   N =< 1 -> S = L
    ;   H is N // 2, '$sitlog_split_at'(H, L, A, B),
        '$swi_merge_sort'(A, Key, Order, SA),
        '$swi_merge_sort'(B, Key, Order, SB),
        '$swi_merge'(SA, SB, Key, Order, S)
    ).
'$swi_merge'([], L, _, _, L) :- !.
'$swi_merge'(L, [], _, _, L) :- !.
'$swi_merge'([X|Xs], [Y|Ys], Key, Order, S) :-
    '$swi_key'(Key, X, KX), '$swi_key'(Key, Y, KY),
    '$swi_compare'(C, KX, KY),
    (   C == (=), ( Order == (<) ; Order == (>) )
    ->  S = [X|S1], '$swi_merge'(Xs, Ys, Key, Order, S1)
    ;   '$swi_before'(Order, C)
    ->  S = [X|S1], '$swi_merge'(Xs, [Y|Ys], Key, Order, S1)
    ;   S = [Y|S1], '$swi_merge'([X|Xs], Ys, Key, Order, S1)
    ).
'$swi_before'(O, C) :- ( O == (<) ; O == (=<) ), !, C \== (>).
'$swi_before'(_, C) :- C \== (<).

% --------------------------------------------------- reading text as terms
% Text is read by sitlog-rs's own reader (SWI-Prolog syntax, the SitLog
% operators), not the engine's: the request goes out on user_error framed
% by \x1\ and \x2\, the host answers on user_input with the term in
% canonical form. So text is read exactly as `sitlogc check` reads files.

'$sitlog_read_text'(Text, Term, Bindings) :-
    '$swi_text_chars'(Text, Cs),
    atom_chars(A, Cs),
    put_char(user_error, '\x1\'),
    put_char(user_error, 'R'),
    write(user_error, A),
    put_char(user_error, '\x2\'),
    flush_output(user_error),
    '$sitlog_read_long'(Reply),
    (   Reply = '$ok'(T, B)
    ->  Term = T, Bindings = B
    ;   Reply = '$error'(E)
    ->  throw(E)
    ;   Term = end_of_file, Bindings = []
    ).

'$swi_read_from_chars'(Text, Term) :- '$sitlog_read_text'(Text, Term, _).
'$swi_read_term_from_atom'(A, Term, _) :- '$sitlog_read_text'(A, Term, _).
'$swi_atom_to_term'(A, Term, Bindings) :- '$sitlog_read_text'(A, Term, Bindings).
'$swi_term_to_atom'(T, A) :-
    (   nonvar(A)
    ->  '$sitlog_read_text'(A, T0, _), T = T0
    ;   write_term_to_chars(T, [quoted(true)], Cs),
        atom_chars(A, Cs)
    ).

% ------------------------------------------------ the KB layer, natively
% (sitlogc run --legacy --legacy-kb native; NativeKb in legacy_kb.rs). A KB is
% a handle '$kb'(N) to a KB of the host; a KB term met where a handle is
% needed becomes one (the last conversion is remembered), and a handle met
% by code the host does not serve becomes the KB term again.

'$sitlog_kb'(Request, Reply) :-
    put_char(user_error, '\x1\'),
    put_char(user_error, 'K'),
    write_canonical(user_error, Request),
    put_char(user_error, '\x2\'),
    flush_output(user_error),
    '$sitlog_read_long'(R),
    (   R = '$ok'(T, _) -> Reply = T
    ;   R = '$error'(E) -> throw(E)
    ;   fail
    ).

'$sitlog_kb_open'(Path, KB) :- '$sitlog_kb'(open(Path), KB).
'$sitlog_kb_save'(Path, KB) :-
    '$sitlog_kb_handle'(KB, H),
    '$sitlog_kb'(save(H, Path), _).

'$sitlog_kb_handle'(KB, H) :-
    (   var(KB)
    ->  throw(error(instantiation_error, kb/1))
    ;   KB = '$kb'(_)
    ->  H = KB
    ;   catch(bb_get('$sitlog_kb_last', T-H0), _, fail), T == KB
    ->  H = H0
    ;   '$sitlog_kb'(handle(KB), H),
        bb_put('$sitlog_kb_last', KB-H)
    ).

% KB is a handle, or a KB term the host reads. Once the host could not read
% a KB (a file or term in a format of its own), KB terms are left to the
% layer's own clauses for the rest of the run (a flag: remembering the
% term would copy it at every call).
'$sitlog_kb_native'(KB) :-
    nonvar(KB),
    (   KB = '$kb'(_)
    ->  true
    ;   '$sitlog_kb_off'
    ->  fail
    ;   catch('$sitlog_kb_handle'(KB, _), error(kb_error(_), native_kb),
              ( '$sitlog_kb_set_off', fail ))
    ).
% The flag: a fact (one call to test it, where a global variable needs a
% catch/3 until it is set); served services test it at every call.
:- dynamic('$sitlog_kb_off'/0).
'$sitlog_kb_set_off' :- ( '$sitlog_kb_off' -> true ; assertz('$sitlog_kb_off') ).

'$sitlog_kb_query'(Name, Args, KB, Answer) :-
    '$sitlog_kb_handle'(KB, H),
    '$sitlog_append'(Args, [_], All),
    Goal =.. [Name|All],
    '$sitlog_kb'(query(H, Goal), A),
    Answer = A.

'$sitlog_kb_update'(Name, Args, KB, New) :-
    '$sitlog_kb_handle'(KB, H),
    Goal =.. [Name|Args],
    '$sitlog_kb'(update(H, Goal), N),
    New = N.

% The arguments with every handle turned into its KB term.
'$sitlog_kb_terms'([], []).
'$sitlog_kb_terms'([A|As], [B|Bs]) :-
    (   nonvar(A), A = '$kb'(_)
    ->  '$sitlog_kb'(term(A), B),
        bb_put('$sitlog_kb_last', B-A)
    ;   B = A
    ),
    '$sitlog_kb_terms'(As, Bs).

% Makes '$swi_X' visible as X: Preds lists Name/Arity.
% The ones whose '$swi_X' is one call of the engine's: X calls it directly
% (get0/2 is called once per character of a file read code by code).
'$swi_inline'(get0(C), get_code(C)).
'$swi_inline'(get0(S, C), get_code(S, C)).

'$sitlog_bridge'([], []).
'$sitlog_bridge'([N/A|Ps], Done) :-
    functor(H, N, A),
    (   catch(predicate_property(H, dynamic), _, fail)
    ->  Done = Done1                     % the application's own
    ;   (   '$swi_inline'(H, B)
        ->  true
        ;   H =.. [_|Args],
            atom_concat('$swi_', N, SN),
            B =.. [SN|Args]
        ),
        catch((assertz((H :- B)), Done = [N/A|Done1]), _, Done = Done1)
    ),
    '$sitlog_bridge'(Ps, Done1).

% ------------------------------------- the native KB layer's asserted rules

% What kb_reach.rs's analysis left to the run (legacy_kb.rs writes these
% facts under --legacy-kb native, none when every predicate is wrapped):
% a rule asserted at run time for a predicate a KB handle may reach turns
% its head's handles into KB terms first; one whose body may get a handle
% (it calls a producer of handles, or a goal unknown until run time) makes
% every predicate of the layer wrapped from then on.
:- dynamic('$sitlog_kb_watch'/0).
:- dynamic('$sitlog_kb_reach'/2).
:- dynamic('$sitlog_kb_producer'/2).
:- dynamic('$sitlog_kb_unwrapped'/1).

'$sitlog_kb_rule'(C, C1) :-
    (   '$sitlog_kb_watch',
        nonvar(C), C = (H :- B), callable(H), H \= (_:_),
        B \== true
    ->  (   '$sitlog_kb_unsure'(B) -> '$sitlog_kb_wrap_all' ; true ),
        functor(H, N, A),
        (   A > 0, '$sitlog_kb_reach'(N, A)
        ->  H =.. [N|As],
            length(Vs, A),
            H2 =.. [N|Vs],
            C1 = (H2 :- '$sitlog_kb_terms'(Vs, As), B)
        ;   C1 = C
        )
    ;   C1 = C
    ).

% Whether goal G may get a handle (coarse: any argument naming a producer).
'$sitlog_kb_unsure'(G) :- var(G), !.
'$sitlog_kb_unsure'(_:_) :- !.
'$sitlog_kb_unsure'(G) :-
    callable(G),
    functor(G, N, A),
    (   '$sitlog_kb_producer'(N, A) -> true
    ;   ( N == call ; N == apply ), A >= 1, arg(1, G, G1), '$sitlog_kb_unsure'(G1) -> true
    ;   A > 0, G =.. [_|As], '$sitlog_kb_unsure_args'(As)
    ).
'$sitlog_kb_unsure_args'([X|Xs]) :-
    (   nonvar(X), callable(X), '$sitlog_kb_unsure'(X) -> true
    ;   nonvar(X), callable(X), functor(X, N, _), '$sitlog_kb_producer'(N, _) -> true
    ;   '$sitlog_kb_unsure_args'(Xs)
    ).

'$sitlog_kb_wrap_all' :-
    (   catch(bb_get('$sitlog_kb_all_wrapped', true), _, fail)
    ->  true
    ;   bb_put('$sitlog_kb_all_wrapped', true),
        (   '$sitlog_kb_unwrapped'(Ps) -> true ; Ps = [] ),
        '$sitlog_kb_wrap_each'(Ps)
    ).
'$sitlog_kb_wrap_each'([]).
'$sitlog_kb_wrap_each'([N/A|Ps]) :-
    '$sitlog_kb_wrap'(N, A),
    '$sitlog_kb_wrap_each'(Ps).

% P's clauses become '$legacy_P''s, P the wrapper legacy_kb.rs writes.
'$sitlog_kb_wrap'(N, A) :-
    '$sitlog_lz_touch'(N, A),
    functor(H, N, A),
    atom_concat('$legacy_', N, L),
    findall(H-B, clause(H, B), Cs),
    retractall(H),
    '$sitlog_kb_moved'(Cs, L),
    H =.. [_|Vs],
    length(Ws, A),
    LV =.. [L|Vs],
    LW =.. [L|Ws],
    assertz((H :- ( '$sitlog_kb_any'(Vs) -> '$sitlog_kb_terms'(Vs, Ws), LW ; LV ))).
'$sitlog_kb_moved'([], _).
'$sitlog_kb_moved'([H-B|Cs], L) :-
    H =.. [_|As],
    LH =.. [L|As],
    assertz((LH :- B)),
    '$sitlog_kb_moved'(Cs, L).
'$sitlog_kb_any'([V|Vs]) :-
    (   nonvar(V), V = '$kb'(_) -> true ; '$sitlog_kb_any'(Vs) ).
