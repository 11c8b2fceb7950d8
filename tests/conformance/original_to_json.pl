% original_to_json.pl: run one SitLog application through the ORIGINAL
% interpreter in test mode and write its result as one JSON object in the
% sitlog-rs convention (semantics.md, "Our convention for sitlogc run
% output").
%
% This file is sitlog-rs code. It loads the original interpreter from
% $SITLOG_HOME at run time and calls its entry points (load/0 and
% execute_md/8); nothing of the original is copied here.
%
% Usage (stdin = the test-mode input terms, e.g. an application's script.txt):
%
%   swipl -q original_to_json.pl APPDIR MAIN_DM IN_ARG MODELS_FILE OUT.json
%
% APPDIR must hold every side file the original opens (basic_actions.pl,
% expectation_types.pl, global_vars.pl, templates.pl, user_functions.pl)
% and the models file; run.sh prepares such a copy. The original's own
% chatter goes to stdout/stderr; only OUT.json is meant to be read.
%
% Departures from a plain run of the original, all on purpose:
% * Reading past the end of the input raises an error (the original loops
%   forever, semantics.md E4); the run is then reported as status "error".
% * out_arg is evaluated once more after the run, with the final globals,
%   no locals and the final history (the original pipes the unevaluated
%   term, E5). If that evaluation fails, the unevaluated term is reported.
% * The history is the list execute_md/8 returns; it is not printed by the
%   original's printer (D-45) but converted term by term.

:- initialization(conformance_run, main).

% The SitLog operators must be in force before the original's files and
% the DMs are read (the original's init file declares the same ones).
:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

:- use_module(library(http/json)).

load_original :-
    (   getenv('SITLOG_HOME', Home)
    ->  true
    ;   format(user_error, "original_to_json: SITLOG_HOME is not set~n", []),
        halt(2)
    ),
    directory_file_path(Home, 'src/init.pl', Init),
    (   exists_file(Init)
    ->  true
    ;   format(user_error, "original_to_json: no ~w~n", [Init]),
        halt(2)
    ),
    % The original's sources produce many style warnings under SWI 7+.
    style_check(-singleton),
    style_check(-discontiguous),
    load_files(user:Init, [silent(true)]).

conformance_run :-
    current_prolog_flag(argv, Argv),
    (   Argv = [AppDir0, MainA, InArgA, Models, OutFile]
    ->  true
    ;   format(user_error,
               "usage: swipl original_to_json.pl APPDIR MAIN IN_ARG MODELS OUT.json~n",
               []),
        halt(2)
    ),
    load_original,
    absolute_file_name(AppDir0, AppDir, [file_type(directory)]),
    directory_file_path(AppDir, 'conformance_log', SaveDir),
    make_directory_path(SaveDir),
    term_to_atom(MainDM, MainA),
    % The original passes the command-line in_arg on as an atom.
    InArg = InArgA,
    setup_original(AppDir, SaveDir, MainDM, InArg, Models),
    run_original(MainDM, InArg, Result),
    result_json(Result, Json),
    setup_call_cleanup(open(OutFile, write, Out),
                       ( json_write(Out, Json, [width(0)]), nl(Out) ),
                       close(Out)),
    halt(0).

% The same facts the original's start_init/0 asserts for a test-mode run
% with default side-file names.
setup_original(AppDir, SaveDir, MainDM, InArg, Models) :-
    assertz(save(false)),
    assertz(mode_exe(test)),
    create_log_file(AppDir, true, 'conformance_log/sitlog.log'),
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

run_original(MainDM, InArg, Result) :-
    % End of input becomes an exception instead of an endless retry loop.
    set_stream(user_input, eof_action(error)),
    global_vars(Globals0),
    catch(( execute_md(MainDM, _Final, InArg, OutArg, Globals0, Globals,
                       [], History)
          ->  (   is_list(History)
              ->  Result = ok(History, OutArg, Globals)
              ;   Result = error('the main DM did not run (unknown DM?)')
              )
          ;   Result = error('execute_md failed')
          ),
          E,
          ( message_to_codes_safe(E, Msg),
            Result = error(Msg) )).

message_to_codes_safe(error(permission_error(input, past_end_of_stream, _), _),
                      'end of input while input was needed') :- !.
message_to_codes_safe(E, Msg) :-
    format(atom(Msg), '~q', [E]).

% Evaluate the piped out_arg (E5) with the original's evaluator.
evaluated_out_arg(OutArg, Globals, History, Value) :-
    catch(( eval_term(OutArg, V, [], _, Globals, _, History) -> true ; fail ),
          _, fail),
    !,
    Value = V.
evaluated_out_arg(OutArg, _, _, OutArg).

result_json(error(Msg), json([status=error, error=Msg, history=[],
                              out_arg= @(null), globals=json([])])).
result_json(ok(History, OutArg, Globals),
            json([status=ok, error= @(null), history=Items,
                  out_arg=OutS, globals=json(GPairs),
                  original_out_arg_unevaluated=RawS])) :-
    maplist(history_item, History, Items),
    term_string_q(OutArg, RawS),
    evaluated_out_arg(OutArg, Globals, History, OutV),
    term_string_q(OutV, OutS),
    globals_pairs(Globals, GPairs).

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
