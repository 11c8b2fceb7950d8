% swi_dump.pl: reads every clause of a file as the original SitLog loader does
% (plain read/1 semantics, SitLog operators declared in `user`) and prints each
% clause with writeq followed by a newline. Named variables print with their
% source name and anonymous ones as `_`, so the dump can be compared with the
% one of `cargo run -p sitlog-syntax --example dump`. On a syntax error the
% reading stops (as in the original) and one line
%     SYNTAX_ERROR <line>:<col> <message>
% is printed (col is 1-based, counted in characters).
%
% With a second argument `all`, reading goes on after a syntax error (SWI
% skips to the end of the erroneous clause), one SYNTAX_ERROR line per error.
%
% Usage: swipl swi_dump.pl FILE [all]

:- op(600, xfx, :).
:- op(800, xfx, =>).
:- op(850, xfx, =>>).
:- op(900, xfx, ==>).

:- initialization(main, main).
:- dynamic go_on/0.

main :-
    current_prolog_flag(argv, [File|Rest]),
    ( Rest == [] ; Rest == [all] ),
    !,
    ( Rest == [all] -> assertz(go_on) ; true ),
    set_stream(user_output, encoding(utf8)),
    setup_call_cleanup(open(File, read, In, [encoding(utf8)]),
                       dump_stream(In),
                       close(In)).
main :-
    format(user_error, "usage: swipl swi_dump.pl FILE~n", []),
    halt(2).

dump_stream(In) :-
    catch(read_term(In, T, [variable_names(Names)]), E, true),
    (   nonvar(E)
    ->  report(E),
        ( go_on -> dump_stream(In) ; true )
    ;   T == end_of_file
    ->  true
    ;   print_clause(T, Names),
        dump_stream(In)
    ).

print_clause(T, Names) :-
    term_variables(T, Vars),
    anonymous(Vars, Names, Anon),
    append(Names, Anon, All),
    write_term(T, [quoted(true), numbervars(true), variable_names(All)]),
    nl.

anonymous([], _, []).
anonymous([V|Vs], Names, Anon) :-
    (   member(_=W, Names), W == V
    ->  Anon = Anon1
    ;   Anon = ['_'=V|Anon1]
    ),
    anonymous(Vs, Names, Anon1).

report(error(syntax_error(Msg), stream(_, Line, LinePos, _))) :-
    !,
    Col is LinePos + 1,
    format("SYNTAX_ERROR ~w:~w ~w~n", [Line, Col, Msg]).
report(error(syntax_error(Msg), file(_, Line, LinePos, _))) :-
    !,
    Col is LinePos + 1,
    format("SYNTAX_ERROR ~w:~w ~w~n", [Line, Col, Msg]).
report(error(syntax_error(Msg), string(_, _))) :-
    !,
    format("SYNTAX_ERROR ?:? ~w~n", [Msg]).
report(E) :-
    format("SYNTAX_ERROR ?:? ~q~n", [E]).
