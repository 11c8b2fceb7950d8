% wrapping.pl: prints, for every situation type of the ORIGINAL SitLog
% interpreter's test mode, what a situation of that type reads and is given,
% from the clauses of communication_int/3 in $SITLOG_HOME/src/in_communication.pl.
%
% This file is sitlog-rs code: it reads the original's clauses at run time
% (nothing of the original is copied here) and runs each clause's body as
% test mode would, with read/1 answering the numbers 1.25, 2.25, ... in turn,
% robot services (rosswipl_*) raising `ros`, and printing, logging and
% sleeping doing nothing; the expectations are left unbound, so that the
% clause's own pattern shows what it needs of them.
%
% Usage: SITLOG_HOME=DIR swipl -q wrapping.pl
% Output, one line per clause, in the file's order:
%
%   NAME/ARITY READS GIVEN      e.g.  detect_body/1 1 detected(1.25)
%   NAME/ARITY fails            (the clause fails, e.g. neutral)
%   NAME/ARITY ros              (it calls a robot service in test mode)
%
% GIVEN is written with writeq, variables as A, B, ...
% runtime/src/testmode/original.rs compares its table with this output.

:- initialization(main, main).
:- dynamic reads/1.

main :-
    (   getenv('SITLOG_HOME', Home)
    ->  true
    ;   format(user_error, "wrapping.pl: SITLOG_HOME is not set~n", []),
        halt(2)
    ),
    (   sub_atom(Home, _, 1, 0, '/') -> Sep = '' ; Sep = '/' ),
    atomic_list_concat([Home, Sep, 'src/in_communication.pl'], File),
    setup_call_cleanup(open(File, read, S), clauses(S, Clauses), close(S)),
    forall(member(C, Clauses), probe(C)).

clauses(S, Clauses) :-
    read_term(S, T, [syntax_errors(dec10)]),
    (   T == end_of_file
    ->  Clauses = []
    ;   Clauses = [T|Rest],
        clauses(S, Rest)
    ).

probe((communication_int(Type, _Expectations, Given) :- Body)) :-
    !,
    test_mode(Body, Goal),
    retractall(reads(_)),
    assertz(reads(0)),
    functor(Type, Name, Arity),
    (   catch(Goal, E, true)
    ->  (   var(E)
        ->  reads(N),
            numbervars(Given, 0, _),
            format("~q/~d ~d ~W~n", [Name, Arity, N, Given,
                                     [quoted(true), numbervars(true)]])
        ;   E == ros
        ->  format("~q/~d ros~n", [Name, Arity])
        ;   format("~q/~d error ~q~n", [Name, Arity, E])
        )
    ;   format("~q/~d fails~n", [Name, Arity])
    ).
probe(_).

% The body as test mode runs it.
test_mode(V, call(V)) :- var(V), !.
test_mode((A, B), (X, Y)) :- !, test_mode(A, X), test_mode(B, Y).
test_mode((A ; B), (X ; Y)) :- !, test_mode(A, X), test_mode(B, Y).
test_mode('|'(A, B), (X ; Y)) :- !, test_mode(A, X), test_mode(B, Y).
test_mode((A -> B), (X -> Y)) :- !, test_mode(A, X), test_mode(B, Y).
test_mode(read(X), next_read(X)) :- !.
test_mode(mode_exe(M), M == test) :- !.
test_mode(otherwise, true) :- !.
test_mode(G, throw(ros)) :-
    functor(G, N, _),
    sub_atom(N, 0, _, _, rosswipl),
    !.
test_mode(G, true) :-
    functor(G, N, _),
    memberchk(N, [print, nl, write, writeln, format, save_info, sleep]),
    !.
test_mode(G, G).

next_read(X) :-
    retract(reads(N)),
    N1 is N + 1,
    assertz(reads(N1)),
    X is N1 + 0.25.
