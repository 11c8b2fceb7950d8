% compare.pl: compare two results in the sitlog-rs JSON convention
% (semantics.md, "Our convention for sitlogc run output").
%
%   swipl -q compare.pl REFERENCE.json CANDIDATE.json [KNOWN_PATH...]
%
% REFERENCE is the original interpreter's result as written by
% original/driver.pl (mode json); CANDIDATE is sitlogc's result (or an
% expected.json).
% Prints `agree` (exit 0) or `DIFFER: PATH: reference R vs candidate C`
% naming the first difference that is not in the KNOWN_PATH list (exit 1).
% Differences at known paths are counted and mentioned after `agree`.
%
% Rules:
% * TERM strings are read with the SitLog operators and compared as terms.
% * Every unbound variable equals every other unbound variable (`_G1`,
%   `_123`, `_` all compare alike).
% * An unbound variable in the *expectation* slot of a reference history
%   entry matches any term: the original leaves the met expectation of
%   perceptual situations unbound (semantics.md E1).
% * status must agree; when both are "error" the messages are not compared
%   (and neither is the rest).
% * globals: same names, same order, matching values.
% Paths look like `history[3].action`, `history[2][0].expectation`,
% `out_arg`, `globals.g_count_fs1`, `status`.

:- initialization(compare_main, main).

:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

:- use_module(library(http/json)).

compare_main :-
    current_prolog_flag(argv, Argv),
    (   Argv = [RefFile, CandFile|Known]
    ->  true
    ;   format(user_error, "usage: swipl compare.pl REF.json CAND.json [KNOWN_PATH...]~n", []),
        halt(2)
    ),
    read_json(RefFile, Ref),
    read_json(CandFile, Cand),
    findall(Path-Msg, difference(Ref, Cand, Path, Msg), Diffs),
    partition(known_diff(Known), Diffs, KnownDiffs, NewDiffs),
    length(KnownDiffs, NK),
    (   NewDiffs = [Path-Msg|_]
    ->  format("DIFFER: ~w: ~w~n", [Path, Msg]),
        halt(1)
    ;   NK =:= 0
    ->  format("agree~n", []),
        halt(0)
    ;   format("agree (~d known divergence(s))~n", [NK]),
        halt(0)
    ).

known_diff(Known, Path-_) :-
    memberchk(Path, Known).

read_json(File, Json) :-
    catch(setup_call_cleanup(open(File, read, In),
                             json_read(In, Json),
                             close(In)),
          E,
          ( print_message(error, E),
            format("DIFFER: cannot read ~w~n", [File]),
            halt(1) )).

field(json(Pairs), Key, Value) :-
    (   memberchk(Key=V, Pairs)
    ->  Value = V
    ;   Value = @(absent)
    ).

% difference(+Ref, +Cand, -Path, -Message): one difference per solution,
% in document order.
difference(Ref, Cand, Path, Msg) :-
    field(Ref, status, RS),
    field(Cand, status, CS),
    (   RS \== CS
    ->  Path = status,
        format(atom(Msg), "reference ~w vs candidate ~w", [RS, CS])
    ;   RS == error
    ->  fail
    ;   difference_ok(Ref, Cand, Path, Msg)
    ).

difference_ok(Ref, Cand, Path, Msg) :-
    field(Ref, history, RH),
    field(Cand, history, CH),
    history_diff(RH, CH, history, Path, Msg).
difference_ok(Ref, Cand, out_arg, Msg) :-
    field(Ref, out_arg, RO),
    field(Cand, out_arg, CO),
    term_diff(RO, CO, plain, Msg).
difference_ok(Ref, Cand, Path, Msg) :-
    field(Ref, globals, RG),
    field(Cand, globals, CG),
    globals_diff(RG, CG, Path, Msg).

history_diff(R, C, Path, Path, Msg) :-
    \+ ( is_list(R), is_list(C) ),
    !,
    format(atom(Msg), "reference ~w vs candidate ~w", [R, C]).
history_diff(R, C, Path0, Path, Msg) :-
    length(R, NR),
    length(C, NC),
    (   NR =\= NC
    ->  Path = Path0,
        format(atom(Msg), "reference has ~d items, candidate ~d", [NR, NC])
    ;   nth0(I, R, RI),
        nth0(I, C, CI),
        format(atom(P1), "~w[~d]", [Path0, I]),
        item_diff(RI, CI, P1, Path, Msg)
    ).

item_diff(R, C, P0, P, Msg) :-
    is_list(R), is_list(C),
    !,
    history_diff(R, C, P0, P, Msg).
item_diff(json(RP), json(CP), P0, P, Msg) :-
    !,
    member(Key, [dm, situation, expectation, action]),
    field(json(RP), Key, RV),
    field(json(CP), Key, CV),
    (   Key == expectation
    ->  Mode = wildcard
    ;   Mode = plain
    ),
    term_diff(RV, CV, Mode, Msg),
    format(atom(P), "~w.~w", [P0, Key]).
item_diff(R, C, P, P, Msg) :-
    format(atom(Msg), "reference ~w vs candidate ~w",
           [item(R), item(C)]).

globals_diff(json(RP), json(CP), Path, Msg) :-
    !,
    maplist(key_of, RP, RK),
    maplist(key_of, CP, CK),
    (   RK \== CK
    ->  Path = globals,
        format(atom(Msg), "reference names ~w vs candidate names ~w", [RK, CK])
    ;   member(K=RV, RP),
        memberchk(K=CV, CP),
        term_diff(RV, CV, plain, Msg),
        format(atom(Path), "globals.~w", [K])
    ).
globals_diff(R, C, globals, Msg) :-
    format(atom(Msg), "reference ~w vs candidate ~w", [R, C]).

key_of(K=_, K).

% term_diff(+RefString, +CandString, +Mode, -Msg): succeeds (once) when
% the two TERM strings differ.
term_diff(R, C, Mode, Msg) :-
    (   parse_term(R, RT), parse_term(C, CT)
    ->  \+ term_match(Mode, RT, CT),
        format(atom(Msg), "reference ~w vs candidate ~w", [R, C])
    ;   R \== C,
        format(atom(Msg), "reference ~w vs candidate ~w (not both terms)", [R, C])
    ).

parse_term(S, T) :-
    ( string(S) ; atom(S) ),
    catch(term_string(T, S), _, fail).

% Top level of an expectation slot: an unbound reference matches anything.
term_match(wildcard, R, _) :-
    var(R),
    !.
term_match(_, R, C) :-
    same_shape(R, C).

same_shape(R, C) :-
    (   var(R)
    ->  var(C)
    ;   var(C)
    ->  fail
    ;   atomic(R)
    ->  R == C
    ;   compound(C),
        compound_name_arity(R, N, A),
        compound_name_arity(C, N, A),
        R =.. [_|RA],
        C =.. [_|CA],
        maplist(same_shape, RA, CA)
    ).
