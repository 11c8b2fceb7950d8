% driver.pl: run one SitLog application through the ORIGINAL interpreter
% in test mode, for tests/conformance/run.sh (mode json) and
% benches/original.sh (mode count); original.sh next to it runs it.
%
% This file is sitlog-rs code. It loads the original interpreter from
% $SITLOG_HOME at run time and calls its entry points (load/0 and
% execute_md/8); nothing of the original is copied here.
%
% Usage (stdin = the test-mode input terms, e.g. an application's
% script.txt, or /dev/null):
%
%   swipl -q driver.pl MODE APPDIR MAIN_DM IN_ARG MODELS_FILE OUT
%
% APPDIR must hold every side file the original opens (basic_actions.pl,
% expectation_types.pl, global_vars.pl, templates.pl, user_functions.pl)
% and the models file; original_prepare in original.sh makes such a copy.
% MAIN_DM and IN_ARG are read as terms (so `main(1000)` and `0` are a
% compound and a number; the original's own command line passes the in_arg
% on as an atom, which for `none`, what run.sh passes, is the same). The
% original's own chatter goes to stdout/stderr; only OUT is meant to be
% read. It is, by MODE:
%
%   json   one JSON object in the sitlog-rs convention (semantics.md, "Our
%          convention for sitlogc run output"): the history converted term
%          by term (not printed by the original's printer, D-45), out_arg
%          evaluated once more after the run with the final globals, no
%          locals and the final history (the original pipes the unevaluated
%          term, E5; if that evaluation fails, the unevaluated term is
%          reported), the final globals; status "error" with a message when
%          the run failed.
%   count  one line `TRANSITIONS SECONDS STATUS`: the number of entries of
%          the returned history with embedded histories flattened, the wall
%          time of execute_md/8 alone, and `ok` or `error(...)`.
%
% The run is the original's plain test mode with the same start-up facts as
% its start_init/0: the history is kept (the original has no switch to drop
% it) and its log file is written as usual, under APPDIR/original_log.
% Only one departure: reading past the end of the input raises an error
% (the original retries forever, semantics.md E4); the run is then an error.

:- initialization(driver_main, main).

% The SitLog operators must be in force before the original's files and
% the DMs are read (the original's init file declares the same ones).
:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

:- use_module(library(http/json)).

driver_main :-
    current_prolog_flag(argv, Argv),
    (   Argv = [Mode, AppDir0, MainA, InArgA, Models, OutFile],
        memberchk(Mode, [json, count])
    ->  true
    ;   format(user_error,
               "usage: swipl driver.pl json|count APPDIR MAIN IN_ARG MODELS OUT~n",
               []),
        halt(2)
    ),
    load_original,
    absolute_file_name(AppDir0, AppDir, [file_type(directory)]),
    directory_file_path(AppDir, 'original_log', SaveDir),
    make_directory_path(SaveDir),
    term_to_atom(MainDM, MainA),
    term_to_atom(InArg, InArgA),
    setup_original(AppDir, SaveDir, MainDM, InArg, Models),
    run_main(MainDM, InArg, Result, Secs),
    setup_call_cleanup(open(OutFile, write, Out),
                       write_result(Mode, Out, Result, Secs),
                       close(Out)),
    halt(0).

load_original :-
    (   getenv('SITLOG_HOME', Home)
    ->  true
    ;   format(user_error, "driver: SITLOG_HOME is not set~n", []),
        halt(2)
    ),
    directory_file_path(Home, 'src/init.pl', Init),
    (   exists_file(Init)
    ->  true
    ;   format(user_error, "driver: no ~w~n", [Init]),
        halt(2)
    ),
    % The original's sources produce many style warnings under SWI 7+.
    style_check(-singleton),
    style_check(-discontiguous),
    load_files(user:Init, [silent(true)]).

% The facts the original's start_init/0 asserts for a test-mode run with
% the default side-file names.
setup_original(AppDir, SaveDir, MainDM, InArg, Models) :-
    assertz(save(false)),
    assertz(mode_exe(test)),
    create_log_file(AppDir, true, 'original_log/sitlog.log'),
    create_dialogue(SaveDir, dm),
    assertz(user:file_search_path(sictusdir, AppDir)),
    assertz(user:file_search_path(projdir, AppDir)),
    assertz(int_arg(InArg)),
    assertz(models(Models)),
    assertz(global_varsf('global_vars.pl')),
    assertz(basic_actions('basic_actions.pl')),
    assertz(templates('templates.pl')),
    assertz(userfunctions('user_functions.pl')),
    assertz(expectationtypes('expectation_types.pl')),
    assertz(knowledge_base(none)),
    assertz(main(MainDM)),
    load.

% Result: ok(History, OutArg, Globals), no_history (execute_md/8 succeeded
% without running the DM), failed, or exception(E); Secs: the wall time of
% execute_md/8.
run_main(MainDM, InArg, Result, Secs) :-
    % End of input becomes an exception instead of an endless retry loop.
    set_stream(user_input, eof_action(error)),
    global_vars(Globals0),
    get_time(T0),
    catch(( execute_md(MainDM, _Final, InArg, OutArg, Globals0, Globals,
                       [], History)
          ->  (   is_list(History)
              ->  Result = ok(History, OutArg, Globals)
              ;   Result = no_history
              )
          ;   Result = failed
          ),
          E,
          Result = exception(E)),
    get_time(T1),
    Secs is T1 - T0.

write_result(json, Out, Result, _Secs) :-
    result_json(Result, Json),
    json_write(Out, Json, [width(0)]),
    nl(Out).
write_result(count, Out, Result, Secs) :-
    (   Result = ok(History, _, _)
    ->  Status = ok,
        flat_length(History, 0, N)
    ;   N = 0,
        count_status(Result, Status)
    ),
    format(Out, "~d ~6f ~q~n", [N, Secs, Status]).

count_status(no_history, error(no_history)).
count_status(failed, error(failed)).
count_status(exception(E), error(E)).

flat_length([], N, N).
flat_length([X|Xs], N0, N) :-
    (   is_list(X)
    ->  flat_length(X, N0, N1)
    ;   N1 is N0 + 1
    ),
    flat_length(Xs, N1, N).

% json mode.

result_json(ok(History, OutArg, Globals),
            json([status=ok, error= @(null), history=Items,
                  out_arg=OutS, globals=json(GPairs),
                  original_out_arg_unevaluated=RawS])) :-
    !,
    maplist(history_item, History, Items),
    term_string_q(OutArg, RawS),
    evaluated_out_arg(OutArg, Globals, History, OutV),
    term_string_q(OutV, OutS),
    globals_pairs(Globals, GPairs).
result_json(Failure, json([status=error, error=Msg, history=[],
                           out_arg= @(null), globals=json([])])) :-
    error_message(Failure, Msg).

error_message(no_history, 'the main DM did not run (unknown DM?)').
error_message(failed, 'execute_md failed').
error_message(exception(error(permission_error(input, past_end_of_stream, _), _)),
              'end of input while input was needed') :- !.
error_message(exception(E), Msg) :-
    format(atom(Msg), '~q', [E]).

% Evaluate the piped out_arg (E5) with the original's evaluator.
evaluated_out_arg(OutArg, Globals, History, Value) :-
    catch(( eval_term(OutArg, V, [], _, Globals, _, History) -> true ; fail ),
          _, fail),
    !,
    Value = V.
evaluated_out_arg(OutArg, _, _, OutArg).

history_item(Sub, Items) :-
    is_list(Sub),
    !,
    maplist(history_item, Sub, Items).
history_item(Dm:(Sit, Exp:Act),
             json([dm=DmS, situation=SitS, expectation=ExpS, action=ActS])) :-
    !,
    term_string_q(Dm, DmS),
    term_string_q(Sit, SitS),
    term_string_q(Exp, ExpS),
    term_string_q(Act, ActS).
history_item(Other, json([unexpected=S])) :-
    term_string_q(Other, S).

globals_pairs(Globals, []) :-
    var(Globals),
    !.
globals_pairs([], []).
globals_pairs([Name ==> Value|Rest], [Name=S|Pairs]) :-
    !,
    term_string_q(Value, S),
    globals_pairs(Rest, Pairs).
globals_pairs([_|Rest], Pairs) :-
    globals_pairs(Rest, Pairs).

term_string_q(T, S) :-
    with_output_to(string(S), writeq(T)).
