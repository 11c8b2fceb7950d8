% calls.pl: the predicates that the ORIGINAL SitLog tree's Prolog code and
% DMs call and do not define, classified as SWI-Prolog defines them.
%
% This file is sitlog-rs code: it reads the original's files at run time
% ($SITLOG_HOME) and keeps nothing of them. Read: every `*.pl` file outside
% src/ (src/ is the interpreter, which sitlog-rs replaces: its predicates
% count as defined, see below) and every `*.dm` file, with the original's
% operators (and any op/3 directive a file holds). Called: every goal of a
% clause body or directive, through the control constructs and the
% meta-predicates' goal arguments (findall/3, forall/2, \+, call/N, once,
% catch/3, maplist/N, include/3, foldl/4..6, ...), and in a DM the goal of
% every apply(Goal, Args). Defined: the heads of the clauses read.
%
% Usage: SITLOG_HOME=DIR swipl -q calls.pl
% Output, one line per predicate called and not defined outside src/,
% sorted:
%
%   swi NAME/ARITY FILE:LINE          a built-in or autoloaded library
%                                     predicate of SWI-Prolog
%   interpreter NAME/ARITY FILE:LINE  defined by the original's src/ only
%   undefined NAME/ARITY FILE:LINE    defined nowhere (not in SWI either)
%
% FILE:LINE is the first place it is called (relative to SITLOG_HOME).

:- initialization(main, main).
:- dynamic called/3, defined/2, src_defined/2.

main :-
    (   getenv('SITLOG_HOME', Home0)
    ->  true
    ;   format(user_error, "calls.pl: SITLOG_HOME is not set~n", []),
        halt(2)
    ),
    (   sub_atom(Home0, _, 1, 0, '/') -> Home = Home0 ; atom_concat(Home0, '/', Home) ),
    sitlog_ops,
    files(Home, '', Files),
    forall(member(F, Files), scan(Home, F)),
    findall(N/A-Where,
            ( called(N/A, Where0, _), \+ defined(N, A),
              once(called(N/A, Where0, _)), Where = Where0 ),
            Pairs0),
    sort(1, @<, Pairs0, Pairs),
    forall(member(P-W, Pairs), report(P, W)).

sitlog_ops :-
    op(600, xfx, :), op(800, xfx, =>), op(850, xfx, =>>), op(900, xfx, ==>).

report(N/A, Where) :-
    functor(H, N, A),
    (   src_defined(N, A) -> Class = interpreter
    ;   swi_defined(H, N, A) -> Class = swi
    ;   Class = undefined
    ),
    format("~w ~q ~w~n", [Class, N/A, Where]).

swi_defined(H, N, A) :-
    (   predicate_property(system:H, defined)
    ->  true
    ;   predicate_property(user:H, multifile)          % file_search_path/2
    ->  true
    ;   '$find_library'(_, N, A, _, _)
    ->  true
    ;   control(N, A)
    ).

control(',', 2). control(';', 2). control('->', 2). control('*->', 2).
control('|', 2). control(!, 0). control(:, 2).

% Files under Dir (relative Rel), sorted; .git and src/ skipped for code.
files(Home, Rel, Files) :-
    atom_concat(Home, Rel, Dir),
    directory_files(Dir, Entries0),
    msort(Entries0, Entries),
    foldl(entry(Home, Rel), Entries, [], Rev),
    reverse(Rev, Files).

entry(_, _, E, Acc, Acc) :- memberchk(E, ['.', '..', '.git']), !.
entry(Home, Rel, E, Acc0, Acc) :-
    atom_concat(Rel, E, Path),
    atom_concat(Home, Path, Abs),
    (   exists_directory(Abs)
    ->  atom_concat(Path, '/', Sub),
        files(Home, Sub, Inner),
        reverse(Inner, RInner),
        append(RInner, Acc0, Acc)
    ;   (   file_name_extension(_, pl, E) ; file_name_extension(_, dm, E) )
    ->  Acc = [Path|Acc0]
    ;   Acc = Acc0
    ).

scan(Home, Rel) :-
    atom_concat(Home, Rel, Abs),
    (   sub_atom(Rel, 0, _, _, 'src/') -> Kind = src
    ;   file_name_extension(_, dm, Rel) -> Kind = dm
    ;   Kind = pl
    ),
    catch(setup_call_cleanup(open(Abs, read, S, [encoding(utf8)]),
                             terms(S, Rel, Kind),
                             close(S)),
          _, true).

terms(S, Rel, Kind) :-
    catch(read_term(S, T, [syntax_errors(dec10), term_position(P)]), _, fail),
    !,
    (   T == end_of_file
    ->  true
    ;   stream_position_data(line_count, P, Line),
        format(atom(Where), '~w:~d', [Rel, Line]),
        term(Kind, T, Where),
        terms(S, Rel, Kind)
    ).
terms(_, _, _).

term(src, (H :- B), _) :- !, head(H, src), asserted(B, src).
term(src, (:- D), _) :- !, asserted(D, src).
term(src, H, _) :- !, head(H, src).
term(dm, T, Where) :- !, applies(T, Where).
term(pl, (:- D), Where) :- !,
    (   D = op(P, Ty, Ns) -> catch(op(P, Ty, Ns), _, true) ; true ),
    goal(D, Where).
term(pl, (H :- B), Where) :- !, head(H, pl), goal(B, Where), asserted(B, pl).
term(pl, (H --> B), Where) :- !, dcg_head(H), dcg_body(B, Where).
term(pl, H, _) :- head(H, pl).

head(H, Kind) :-
    (   callable(H), \+ H = (_:_)
    ->  functor(H, N, A),
        (   Kind == src
        ->  ( src_defined(N, A) -> true ; assertz(src_defined(N, A)) )
        ;   ( defined(N, A) -> true ; assertz(defined(N, A)) )
        )
    ;   true
    ).

% Facts asserted by a body (mode_exe/1, asserted by the interpreter at
% start-up) count as defined where the body is.
asserted(B, Kind) :-
    forall(( sub_term(G, B), compound(G), G =.. [F, C],
             memberchk(F, [assert, asserta, assertz]),
             nonvar(C), ( C = (H :- _) -> true ; H = C ) ),
           head(H, Kind)).

dcg_head(H) :-
    (   callable(H) -> functor(H, N, A0), A is A0 + 2, head_na(N, A) ; true ).
head_na(N, A) :- ( defined(N, A) -> true ; assertz(defined(N, A)) ).

dcg_body(V, _) :- var(V), !.
dcg_body((A, B), W) :- !, dcg_body(A, W), dcg_body(B, W).
dcg_body((A ; B), W) :- !, dcg_body(A, W), dcg_body(B, W).
dcg_body((A | B), W) :- !, dcg_body(A, W), dcg_body(B, W).
dcg_body((A -> B), W) :- !, dcg_body(A, W), dcg_body(B, W).
dcg_body({G}, W) :- !, goal(G, W).
dcg_body(L, _) :- ( L == [] ; L = [_|_] ; string(L) ; L == ! ), !.
dcg_body(\+ G, W) :- !, dcg_body(G, W).
dcg_body(G, W) :- callable(G), !, extra(G, 2, W).
dcg_body(_, _).

% apply(Goal, Args) anywhere in a DM term.
applies(T, _) :- var(T), !.
applies(apply(G, _), W) :- !, ( callable(G) -> call_of(G, W) ; true ).
applies(T, W) :- compound(T), !, T =.. [_|Args], forall(member(A, Args), applies(A, W)).
applies(_, _).

call_of(G, W) :-
    functor(G, N, A),
    ( called(N/A, _, _) -> true ; assertz(called(N/A, W, x)) ).

% extra(Closure, K, Where): Closure called with K more arguments.
extra(C, K, W) :-
    (   var(C) -> true
    ;   C = _:C1 -> extra(C1, K, W)
    ;   atom(C) -> ( called(C/K, _, _) -> true ; assertz(called(C/K, W, x)) )
    ;   compound(C) -> functor(C, N, A0), A is A0 + K,
        ( called(N/A, _, _) -> true ; assertz(called(N/A, W, x)) )
    ;   true
    ).

goal(V, _) :- var(V), !.
goal(_:G, W) :- !, goal(G, W).
goal(G, _) :- \+ callable(G), !.
goal(G, W) :-
    call_of(G, W),
    forall(meta(G, Sub, K), ( K =:= 0 -> goal(Sub, W) ; extra(Sub, K, W) )).

% meta(Goal, Argument, K): Argument is a goal called with K more arguments.
meta((A, B), G, 0) :- ( G = A ; G = B ).
meta((A ; B), G, 0) :- ( G = A ; G = B ).
meta((A | B), G, 0) :- ( G = A ; G = B ).
meta((A -> B), G, 0) :- ( G = A ; G = B ).
meta((A *-> B), G, 0) :- ( G = A ; G = B ).
meta(\+ A, A, 0).
meta(not(A), A, 0).
meta(call(A), A, 0).
meta(once(A), A, 0).
meta(ignore(A), A, 0).
meta(forall(A, B), G, 0) :- ( G = A ; G = B ).
meta(findall(_, A, _), A, 0).
meta(findall(_, A, _, _), A, 0).
meta(aggregate_all(_, A, _), A, 0).
meta(bagof(_, A, _), G, 0) :- strip(A, G).
meta(setof(_, A, _), G, 0) :- strip(A, G).
meta(catch(A, _, B), G, 0) :- ( G = A ; G = B ).
meta(setup_call_cleanup(A, B, C), G, 0) :- ( G = A ; G = B ; G = C ).
meta(call_cleanup(A, B), G, 0) :- ( G = A ; G = B ).
meta(with_output_to(_, A), A, 0).
meta(time(A), A, 0).
meta(assert(_), _, _) :- fail.
meta(T, C, K) :- T =.. [call, C|Args], Args \== [], length(Args, K).
meta(T, C, K) :- T =.. [maplist, C|Lists], Lists \== [], length(Lists, K).
meta(include(C, _, _), C, 1).
meta(exclude(C, _, _), C, 1).
meta(partition(C, _, _, _), C, 1).
meta(T, C, K) :- T =.. [foldl, C|Rest], length(Rest, L), L >= 3, K is L - 1.
meta(predsort(C, _, _), C, 3).

strip(V, V) :- var(V), !.
strip(_^A, G) :- !, strip(A, G).
strip(A, A).
