% original_driver.pl: run one SitLog application through the ORIGINAL
% interpreter in test mode, for benches/original.sh.
%
% This file is sitlog-rs code. Like tests/conformance/original_to_json.pl
% it loads the original interpreter from $SITLOG_HOME at run time and calls
% its entry points (load/0 and execute_md/8); nothing of the original is
% copied here.
%
% Usage (stdin = the test-mode input terms, or /dev/null):
%
%   swipl -q original_driver.pl APPDIR MAIN_DM IN_ARG MODELS RESULT
%
% MAIN_DM and IN_ARG are read as terms (so `main(1000)` and `0` are a
% compound and a number; the original's own command line would pass the
% in_arg on as an atom). RESULT gets one line `TRANSITIONS SECONDS STATUS`:
% the number of entries of the returned history with embedded histories
% flattened, the wall time of execute_md/8 alone, and `ok` or `error(...)`.
%
% The run is the original's plain test mode with the same start-up facts as
% its start_init/0 (and as original_to_json.pl): the history is kept (the
% original has no switch to drop it) and its log file is written as usual.
% Only one departure: reading past the end of the input is an error
% instead of an endless retry loop.

:- initialization(driver_main, main).

:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

driver_main :-
    current_prolog_flag(argv, Argv),
    (   Argv = [AppDir0, MainA, InArgA, Models, ResultFile]
    ->  true
    ;   format(user_error,
               "usage: swipl original_driver.pl APPDIR MAIN IN_ARG MODELS RESULT~n",
               []),
        halt(2)
    ),
    load_original,
    absolute_file_name(AppDir0, AppDir, [file_type(directory)]),
    directory_file_path(AppDir, 'bench_log', SaveDir),
    make_directory_path(SaveDir),
    term_to_atom(MainDM, MainA),
    term_to_atom(InArg, InArgA),
    setup_original(AppDir, SaveDir, MainDM, InArg, Models),
    run_main(MainDM, InArg, Status, N, Secs),
    setup_call_cleanup(open(ResultFile, write, Out),
                       format(Out, "~d ~6f ~q~n", [N, Secs, Status]),
                       close(Out)),
    halt(0).

load_original :-
    (   getenv('SITLOG_HOME', Home)
    ->  true
    ;   format(user_error, "original_driver: SITLOG_HOME is not set~n", []),
        halt(2)
    ),
    directory_file_path(Home, 'src/init.pl', Init),
    (   exists_file(Init)
    ->  true
    ;   format(user_error, "original_driver: no ~w~n", [Init]),
        halt(2)
    ),
    style_check(-singleton),
    style_check(-discontiguous),
    load_files(user:Init, [silent(true)]).

% The facts the original's start_init/0 asserts for a test-mode run with
% the default side-file names.
setup_original(AppDir, SaveDir, MainDM, InArg, Models) :-
    assertz(save(false)),
    assertz(mode_exe(test)),
    create_log_file(AppDir, true, 'bench_log/sitlog.log'),
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

run_main(MainDM, InArg, Status, N, Secs) :-
    set_stream(user_input, eof_action(error)),
    global_vars(Globals0),
    get_time(T0),
    catch(( execute_md(MainDM, _Final, InArg, _OutArg, Globals0, _Globals,
                       [], History)
          ->  (   is_list(History)
              ->  Status = ok
              ;   Status = error(no_history), History = []
              )
          ;   Status = error(failed), History = []
          ),
          E,
          ( Status = error(E), History = [] )),
    get_time(T1),
    Secs is T1 - T0,
    flat_length(History, 0, N).

flat_length([], N, N).
flat_length([X|Xs], N0, N) :-
    (   is_list(X)
    ->  flat_length(X, N0, N1)
    ;   N1 is N0 + 1
    ),
    flat_length(Xs, N1, N).
