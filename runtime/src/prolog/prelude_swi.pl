% prelude_swi.pl: the second part of the prelude (consulted right after
% prelude.pl, into the same module): SWI-Prolog's strings and text
% predicates, format/1,2,3 as SWI's, Edinburgh I/O, file names, time and
% statistics, and a few more built-ins the engine lacks. Each '$swi_X' is
% made visible as X like those of prelude.pl (list in swi.rs).
%
% SWI-Prolog strings are atoms here: the engine has no string type, and
% what a task sees of a string (its text, written) is an atom's. Every
% predicate below gives an atom where SWI gives a string and accepts any
% text (atom, number, code list, char list) where SWI accepts text.

:- use_module(library(files), []).

% Text as an atom.
'$swi_text_atom'(X, A) :-
    (   atom(X) -> A = X
    ;   '$swi_text_chars'(X, Cs), atom_chars(A, Cs)
    ).

% ----------------------------------------------------------------- strings

% atom_string(?Atom, ?String).
'$swi_atom_string'(A, S) :-
    (   nonvar(A)
    ->  '$swi_text_atom'(A, S0), S = S0
    ;   '$swi_text_atom'(S, A)
    ).

% string_concat(?S1, ?S2, ?S3): nondeterministic when S3 alone is given.
'$swi_string_concat'(A, B, C) :-
    (   nonvar(A), nonvar(B)
    ->  '$swi_text_chars'(A, As), '$swi_text_chars'(B, Bs),
        '$sitlog_append'(As, Bs, Cs), atom_chars(C0, Cs), C = C0
    ;   '$swi_text_atom'(C, CA),
        '$swi_bound_atom'(A, A1), '$swi_bound_atom'(B, B1),
        atom_concat(A1, B1, CA),
        A = A1, B = B1
    ).

'$swi_bound_atom'(X, A) :- ( var(X) -> true ; '$swi_text_atom'(X, A) ).

% text_concat(?T1, ?T2, ?T3).
'$swi_text_concat'(A, B, C) :- '$swi_string_concat'(A, B, C).

% string_chars(?String, ?Chars), string_codes(?String, ?Codes).
'$swi_string_chars'(S, Cs) :-
    (   nonvar(S) -> '$swi_text_chars'(S, Cs0), Cs = Cs0
    ;   atom_chars(S, Cs)
    ).
'$swi_string_codes'(S, Cs) :-
    (   nonvar(S) -> '$swi_text_chars'(S, Ch), '$swi_chars_codes'(Ch, Cs0), Cs = Cs0
    ;   atom_codes(S, Cs)
    ).

% string_to_atom(?String, ?Atom).
'$swi_string_to_atom'(S, A) :-
    (   nonvar(S) -> '$swi_text_atom'(S, A0), A = A0
    ;   '$swi_text_atom'(A, S)
    ).

% text_to_string(+Text, -String).
'$swi_text_to_string'(T, S) :- '$swi_text_atom'(T, S0), S = S0.

% string_length(+String, -Length).
'$swi_string_length'(S, L) :- '$swi_text_chars'(S, Cs), lists:length(Cs, L).

% string_code(+Index, +String, -Code): 1-based; fails out of range.
'$swi_string_code'(I, S, C) :-
    '$swi_text_chars'(S, Cs),
    integer(I), I >= 1,
    lists:nth1(I, Cs, Ch),
    char_code(Ch, C).

% number_string(?Number, ?String): white space around the number is allowed.
'$swi_number_string'(N, S) :-
    (   nonvar(S)
    ->  '$swi_text_chars'(S, Cs0),
        '$swi_strip'(Cs0, [' ', '\t', '\n', '\r'], Cs),
        catch(number_chars(N0, Cs), error(syntax_error(_), _), fail),
        N = N0
    ;   number_chars(N, Cs), atom_chars(S, Cs)
    ).

% string_lower(+String, -Lower), string_upper(+String, -Upper).
'$swi_string_lower'(S, L) :- '$swi_text_atom'(S, A), '$swi_downcase_atom'(A, L).
'$swi_string_upper'(S, U) :- '$swi_text_atom'(S, A), '$swi_upcase_atom'(A, U).

% sub_string(+String, ?Before, ?Length, ?After, ?Sub).
'$swi_sub_string'(S, B, L, A, Sub) :-
    '$swi_text_atom'(S, SA),
    '$swi_bound_atom'(Sub, SubA),
    sub_atom(SA, B, L, A, SubA),
    Sub = SubA.

% split_string(+String, +SepChars, +Pad, -SubStrings): split at every
% separator, then strip the pad characters off both ends of each part.
'$swi_split_string'(S, Sep, Pad, Subs) :-
    '$swi_text_chars'(S, Cs),
    '$swi_text_chars'(Sep, SepCs),
    '$swi_text_chars'(Pad, PadCs),
    (   SepCs == []
    ->  Parts = [Cs]
    ;   '$swi_split_at'(Cs, SepCs, Parts)
    ),
    '$swi_stripped_atoms'(Parts, PadCs, Subs0),
    Subs = Subs0.

'$swi_split_at'(Cs, Seps, [Part|Parts]) :-
    '$swi_upto_sep'(Cs, Seps, Part, Rest),
    (   Rest = [_|After]
    ->  '$swi_split_at'(After, Seps, Parts)
    ;   Parts = []
    ).
'$swi_upto_sep'([], _, [], []).
'$swi_upto_sep'([C|Cs], Seps, Part, Rest) :-
    (   lists:memberchk(C, Seps)
    ->  Part = [], Rest = [C|Cs]
    ;   Part = [C|Part1], '$swi_upto_sep'(Cs, Seps, Part1, Rest)
    ).

'$swi_stripped_atoms'([], _, []).
'$swi_stripped_atoms'([P|Ps], Pad, [A|As]) :-
    '$swi_strip'(P, Pad, S), atom_chars(A, S),
    '$swi_stripped_atoms'(Ps, Pad, As).

% The chars without the leading and trailing ones in Pad.
'$swi_strip'(Cs, Pad, S) :-
    '$swi_drop_pad'(Cs, Pad, Cs1),
    lists:reverse(Cs1, R1),
    '$swi_drop_pad'(R1, Pad, R2),
    lists:reverse(R2, S).
'$swi_drop_pad'([C|Cs], Pad, R) :- lists:memberchk(C, Pad), !, '$swi_drop_pad'(Cs, Pad, R).
'$swi_drop_pad'(Cs, _, Cs).

% term_string(?Term, ?String), term_string(?Term, ?String, +Options):
% text is read by our reader (see '$sitlog_read_text'/3).
'$swi_term_string'(T, S) :- '$swi_term_string'(T, S, []).
'$swi_term_string'(T, S, _) :-
    (   nonvar(S)
    ->  '$sitlog_read_text'(S, T0, _), T = T0
    ;   write_term_to_chars(T, [quoted(true)], Cs), atom_chars(S, Cs)
    ).

% sformat(-String, +Format, +Args), sformat(-String, +Format).
'$swi_sformat'(S, F, A) :- '$swi_format'(atom(S), F, A).
'$swi_sformat'(S, F) :- '$swi_format'(atom(S), F, []).

% ------------------------------------------------------------------ format
% format/1,2,3 as SWI's: the format is any text, the arguments a list or a
% single term, and the output a stream or atom(A), string(S), codes(C),
% codes(C, Tail), chars(C), chars(C, Tail). The directives the engine's
% format//2 lacks or reads otherwise are turned into ones it has: ~p
% (print/1, i.e. ~q), ~c and ~Nc (a code N times), ~e and ~g (C's printf),
% ~s given codes, ~a given a number, ~* (the numeric argument from Args).

'$swi_format'(F) :- '$swi_format'(F, []).
'$swi_format'(F, A) :-
    current_output(S),
    '$swi_format'(S, F, A).
'$swi_format'(Sink, F, A) :-
    '$swi_format_chars'(F, A, Cs),
    (   var(Sink) -> throw(error(instantiation_error, format/3))
    ;   Sink = atom(X) -> atom_chars(X0, Cs), X = X0
    ;   Sink = string(X) -> atom_chars(X0, Cs), X = X0
    ;   Sink = codes(X) -> '$swi_chars_codes'(Cs, X)
    ;   Sink = codes(X, T) -> '$swi_chars_codes'(Cs, C0), '$sitlog_append'(C0, T, X)
    ;   Sink = chars(X) -> X = Cs
    ;   Sink = chars(X, T) -> '$sitlog_append'(Cs, T, X)
    ;   '$swi_put_chars'(Sink, Cs)
    ).

'$swi_put_chars'(_, []).
'$swi_put_chars'(S, [C|Cs]) :- put_char(S, C), '$swi_put_chars'(S, Cs).

'$swi_format_chars'(F, A, Cs) :-
    '$swi_text_chars'(F, F0),
    (   A == [] -> Args0 = []
    ;   nonvar(A), A = [_|_] -> Args0 = A
    ;   Args0 = [A]
    ),
    '$swi_fmt'(F0, Args0, F1, Args1),
    format:format_(F1, Args1, Cs, []).

% '$swi_fmt'(+Format, +Args, -Format1, -Args1).
'$swi_fmt'([], As, [], As).
'$swi_fmt'([~|F0], As0, F, As) :- !,
    '$swi_fmt_num'(F0, As0, Num, [D|F1], As1),
    '$swi_fmt_directive'(D, Num, F1, As1, F, As).
'$swi_fmt'([C|F0], As0, [C|F], As) :- '$swi_fmt'(F0, As0, F, As).

% The numeric argument of a directive: digits, `*` (from Args), or none.
'$swi_fmt_num'(['*'|F], [N|As], num(N), F, As) :- !.
'$swi_fmt_num'(['`', C|F], As, fill(C), F, As) :- !.
'$swi_fmt_num'(F0, As, Num, F, As) :-
    '$swi_digits'(F0, Ds, F),
    (   Ds == [] -> Num = none ; number_chars(N, Ds), Num = num(N) ).
'$swi_digits'([D|F0], [D|Ds], F) :- '0' @=< D, D @=< '9', !, '$swi_digits'(F0, Ds, F).
'$swi_digits'(F, [], F).

'$swi_fmt_directive'(p, Num, F1, As1, F, As) :- !,
    '$swi_fmt_directive'(q, Num, F1, As1, F, As).
'$swi_fmt_directive'(c, Num, F1, [Code|As1], F, [Cs|As]) :- !,
    ( Num = num(N) -> true ; N = 1 ),
    char_code(Ch, Code),
    lists:length(Cs, N), lists:maplist(=(Ch), Cs),
    F = [~, s|F2],
    '$swi_fmt'(F1, As1, F2, As).
'$swi_fmt_directive'(s, Num, F1, [Text|As1], F, [Cs|As]) :- !,
    '$swi_text_chars'(Text, Cs),
    '$swi_fmt_prefix'(Num, s, F, F2),
    '$swi_fmt'(F1, As1, F2, As).
'$swi_fmt_directive'(a, Num, F1, [X|As1], F, [A|As]) :- !,
    '$swi_text_atom'(X, A),
    '$swi_fmt_prefix'(Num, a, F, F2),
    '$swi_fmt'(F1, As1, F2, As).
'$swi_fmt_directive'(D, Num, F1, [X|As1], [~, s|F2], [Cs|As]) :-
    ( D == e ; D == g ), !,
    ( Num = num(P) -> true ; P = 6 ),
    Y is float(X),
    '$swi_printf'(D, P, Y, Cs),
    '$swi_fmt'(F1, As1, F2, As).
'$swi_fmt_directive'(f, Num, F1, [X|As1], F, [Y|As]) :- !,
    Y is float(X),
    '$swi_fmt_prefix'(Num, f, F, F2),
    '$swi_fmt'(F1, As1, F2, As).
'$swi_fmt_directive'(D, Num, F1, As0, F, As) :-
    '$swi_fmt_prefix'(Num, D, F, F2),
    (   lists:memberchk(D, [w, q, d, 'D', r, 'R', i, 'U', 'L'])
    ->  As0 = [X|As1], As = [X|As2]
    ;   As1 = As0, As = As2
    ),
    '$swi_fmt'(F1, As1, F2, As2).

% The directive back, with its numeric argument as digits.
'$swi_fmt_prefix'(none, D, [~, D|F], F).
'$swi_fmt_prefix'(num(N), D, F0, F) :-
    number_chars(N, Ds),
    '$sitlog_append'([~|Ds], [D|F], F0).
'$swi_fmt_prefix'(fill(C), D, [~, '`', C, D|F], F).

% C's printf %.Pe and %.Pg of a float.
'$swi_printf'(e, P, X, Cs) :-
    '$swi_mantissa'(X, P, M, E),
    '$swi_fixed'(M, P, Ms),
    '$swi_exp_chars'(E, Es),
    '$sitlog_append'(Ms, [e|Es], Cs).
'$swi_printf'(g, P0, X, Cs) :-
    ( P0 =:= 0 -> P = 1 ; P = P0 ),
    (   X =:= 0
    ->  Cs = ['0']
    ;   P1 is P - 1,
        '$swi_mantissa'(X, P1, _, E),
        (   ( E < -4 ; E >= P )
        ->  '$swi_mantissa'(X, P1, M, E),
            '$swi_fixed'(M, P1, Ms0),
            '$swi_trim_zeros'(Ms0, Ms),
            '$swi_exp_chars'(E, Es),
            '$sitlog_append'(Ms, [e|Es], Cs)
        ;   D is max(0, P1 - E),
            '$swi_fixed'(X, D, Cs0),
            '$swi_trim_zeros'(Cs0, Cs)
        )
    ).

% X = M * 10^E with 1 =< |M| < 10 once rounded to P decimals.
'$swi_mantissa'(X, P, M, E) :-
    (   X =:= 0
    ->  M = 0.0, E = 0
    ;   A is abs(X),
        '$swi_norm'(A, 0, M0, E0),
        '$swi_pow10'(P, 1, TP),
        R is round(M0 * TP) / TP,
        (   R >= 10 -> M1 is M0 / 10, E is E0 + 1 ; M1 = M0, E = E0 ),
        ( X < 0 -> M is - M1 ; M = M1 )
    ).
'$swi_norm'(A, E0, M, E) :-
    (   A >= 10 -> A1 is A / 10, E1 is E0 + 1, '$swi_norm'(A1, E1, M, E)
    ;   A < 1 -> A1 is A * 10, E1 is E0 - 1, '$swi_norm'(A1, E1, M, E)
    ;   M = A, E = E0
    ).
'$swi_pow10'(N, T0, T) :-
    ( N =< 0 -> T = T0 ; T1 is T0 * 10, N1 is N - 1, '$swi_pow10'(N1, T1, T) ).

% X with P decimals (rounded half away from zero), as chars.
'$swi_fixed'(X, P, Cs) :-
    '$swi_pow10'(P, 1, T),
    N is round(abs(X) * T),
    number_chars(N, Ds0),
    lists:length(Ds0, L),
    (   L =< P
    ->  Z is P + 1 - L, lists:length(Zs, Z), lists:maplist(=('0'), Zs),
        '$sitlog_append'(Zs, Ds0, Ds)
    ;   Ds = Ds0
    ),
    lists:length(Ds, L1),
    I is L1 - P,
    '$sitlog_split_at'(I, Ds, Int, Frac),
    ( Frac == [] -> Body = Int ; '$sitlog_append'(Int, ['.'|Frac], Body) ),
    ( X < 0, N > 0 -> Cs = [-|Body] ; Cs = Body ).

'$swi_exp_chars'(E, [S|Ds]) :-
    ( E < 0 -> S = (-) ; S = (+) ),
    A is abs(E),
    number_chars(A, Ds0),
    ( Ds0 = [_] -> Ds = ['0'|Ds0] ; Ds = Ds0 ).
'$swi_trim_zeros'(Cs, T) :-
    (   lists:memberchk('.', Cs)
    ->  lists:reverse(Cs, R0),
        '$swi_drop_pad'(R0, ['0'], R1),
        ( R1 = ['.'|R2] -> true ; R2 = R1 ),
        lists:reverse(R2, T)
    ;   T = Cs
    ).

% ---------------------------------------------------------- other built-ins

% is_list(@Term): a proper list.
'$swi_is_list'(X) :- var(X), !, fail.
'$swi_is_list'([]) :- !.
'$swi_is_list'([_|T]) :- '$swi_is_list'(T).

% name(?AtomOrNumber, ?Codes): a number when the codes read as one.
'$swi_name'(X, Codes) :-
    (   nonvar(X)
    ->  '$swi_text_chars'(X, Cs), '$swi_chars_codes'(Cs, Codes0), Codes = Codes0
    ;   '$swi_codes_chars'(Codes, Cs),
        (   catch(number_chars(N, Cs), _, fail) -> X = N ; atom_chars(X, Cs) )
    ).

% random(+L, +U, -R) (library(random)): L =< R < U, integers or floats.
'$swi_random'(L, U, R) :-
    random(F),
    (   integer(L), integer(U)
    ->  R is L + floor(F * (U - L))
    ;   R is L + F * (U - L)
    ).
% random_between(+L, +U, -R): L =< R =< U.
'$swi_random_between'(L, U, R) :- U1 is U + 1, '$swi_random'(L, U1, R).

% tab(+N), tab(+Stream, +N).
'$swi_tab'(N) :- current_output(S), '$swi_tab'(S, N).
'$swi_tab'(S, N0) :- N is N0, '$swi_spaces'(S, N).
'$swi_spaces'(S, N) :- ( N > 0 -> put_char(S, ' '), N1 is N - 1, '$swi_spaces'(S, N1) ; true ).

% Edinburgh I/O: see/1, seeing/1, seen/0, tell/1, telling/1, told/0. Only
% the streams they opened are closed (never the engine's own), and `user`
% is the stream that was current before the first of them (the engine's
% set_input/1 also moves the user_input alias).
'$swi_user'(Kind, U) :-
    atom_concat('$swi_user_', Kind, K),
    (   catch(bb_get(K, U0), _, fail) -> U = U0
    ;   ( Kind == see -> A = user_input ; A = user_output ),
        stream_property(U, alias(A)),
        bb_put(K, U)
    ).
'$swi_see'(F) :-
    '$swi_user'(see, U),
    (   F == user -> set_input(U)
    ;   atom(F), '$swi_opened'(see, F, S) -> set_input(S)
    ;   '$swi_text_atom'(F, A), open(A, read, S),
        '$swi_open'(see, A, S), set_input(S)
    ).
'$swi_seeing'(F) :-
    current_input(S),
    ( '$swi_opened'(see, F0, S) -> F = F0 ; F = user ).
'$swi_seen' :-
    current_input(S),
    ( '$swi_opened'(see, F, S) -> '$swi_close'(see, F), close(S) ; true ),
    '$swi_user'(see, U),
    set_input(U).
% read(-Term): from a file see/1 opened, as read/1; else the run's next
% input (the next term of the script, or typed), as the original's test
% mode reads it (the host answers an `I` request); end_of_file at its end.
'$swi_read'(Term) :-
    current_input(S),
    '$swi_opened'(see, _, S),
    !,
    read(S, Term).
'$swi_read'(Term) :-
    put_char(user_error, '\x1\'),
    put_char(user_error, 'I'),
    put_char(user_error, '\x2\'),
    flush_output(user_error),
    get_line_to_chars(user_input, Line, []),
    read_from_chars(Line, Reply),
    (   Reply = '$ok'(T, _)
    ->  Term = T
    ;   Reply = '$error'(E)
    ->  throw(E)
    ;   Term = end_of_file
    ).

'$swi_tell'(F) :-
    '$swi_user'(tell, U),
    (   F == user -> set_output(U)
    ;   atom(F), '$swi_opened'(tell, F, S) -> set_output(S)
    ;   '$swi_text_atom'(F, A), open(A, write, S),
        '$swi_open'(tell, A, S), set_output(S)
    ).
'$swi_telling'(F) :-
    current_output(S),
    ( '$swi_opened'(tell, F0, S) -> F = F0 ; F = user ).
'$swi_told' :-
    current_output(S),
    ( '$swi_opened'(tell, F, S) -> '$swi_close'(tell, F), close(S) ; true ),
    '$swi_user'(tell, U),
    set_output(U).

'$swi_opened'(Kind, F, S) :-
    '$swi_edinburgh'(L),
    lists:member(Kind-F-S0, L), S0 == S, !.
'$swi_opened'(Kind, F, S) :-
    var(S),
    '$swi_edinburgh'(L),
    lists:member(Kind-F-S, L), !.
'$swi_edinburgh'(L) :- ( catch(bb_get('$swi_edinburgh', L0), _, fail) -> L = L0 ; L = [] ).
'$swi_open'(Kind, F, S) :-
    '$swi_edinburgh'(L),
    bb_put('$swi_edinburgh', [Kind-F-S|L]).
'$swi_close'(Kind, F) :-
    '$swi_edinburgh'(L),
    '$swi_without'(L, Kind-F, L1),
    bb_put('$swi_edinburgh', L1).
'$swi_without'([], _, []).
'$swi_without'([K-F-S|L], KF, R) :-
    ( K-F == KF -> R = R1 ; R = [K-F-S|R1] ),
    '$swi_without'(L, KF, R1).

% file_search_path(?Alias, ?Path): SWI's user-extensible table (dynamic).
'$swi_file_search_path'(_, _) :- fail.

% absolute_file_name(+Spec, -Absolute), absolute_file_name(+Spec, -Absolute,
% +Options): Spec is text or Alias(Sub) (file_search_path/2); relative to
% the option relative_to(FileOrDir), else to the working directory;
% extensions(Exts) and access(Mode) / file_type(directory) pick the first
% candidate that exists; `.` and `..` are resolved.
'$swi_absolute_file_name'(Spec, Abs) :- '$swi_absolute_file_name'(Spec, Abs, []).
'$swi_absolute_file_name'(Spec, Abs, Options) :-
    (   compound(Spec), Spec =.. [Alias, Sub], \+ Spec = [_|_]
    ->  catch(file_search_path(Alias, Dir0), _, fail),
        '$swi_text_chars'(Sub, SubCs),
        '$swi_text_chars'(Dir0, DirCs),
        '$sitlog_append'(DirCs, ['/'|SubCs], Cs0),
        '$swi_absolute_file_name'(Cs0, Abs, Options)
    ;   '$swi_text_chars'(Spec, Cs0),
        (   Cs0 = ['/'|_]
        ->  Path0 = Cs0
        ;   '$swi_base_dir'(Options, Base),
            '$sitlog_append'(Base, ['/'|Cs0], Path0)
        ),
        '$swi_normal_path'(Path0, Path),
        (   lists:memberchk(extensions(Exts), Options) -> true ; Exts = [''] ),
        '$swi_candidates'(Exts, Path, Cands),
        (   ( lists:memberchk(access(M), Options), M \== none ; lists:memberchk(file_type(_), Options) )
        ->  lists:member(C, Cands), '$swi_exists'(C, Options), !
        ;   Cands = [C|_]
        ),
        atom_chars(Abs0, C),
        Abs = Abs0
    ).

'$swi_base_dir'(Options, Base) :-
    (   lists:memberchk(relative_to(R), Options)
    ->  '$swi_text_chars'(R, RCs),
        (   files:directory_exists(RCs)
        ->  Base = RCs
        ;   '$swi_dir_of'(RCs, Base)
        )
    ;   files:working_directory(Base0, Base0),
        ( '$sitlog_append'(Base, ['/'], Base0) -> true ; Base = Base0 )
    ).
'$swi_dir_of'(Cs, Dir) :-
    lists:reverse(Cs, R),
    (   '$sitlog_append'(_, ['/'|RDir], R) -> lists:reverse(RDir, Dir) ; Dir = ['.'] ).

'$swi_candidates'([], _, []).
'$swi_candidates'([E|Es], Path, [C|Cs]) :-
    '$swi_text_chars'(E, ECs),
    (   ECs == [] -> C = Path
    ;   ECs = ['.'|_] -> '$sitlog_append'(Path, ECs, C)
    ;   '$sitlog_append'(Path, ['.'|ECs], C)
    ),
    '$swi_candidates'(Es, Path, Cs).
'$swi_exists'(C, Options) :-
    (   lists:memberchk(file_type(directory), Options) -> files:directory_exists(C)
    ;   files:file_exists(C)
    ).

% Resolve `.`, `..` and empty segments of an absolute path.
'$swi_normal_path'(['/'|Cs], Path) :-
    '$swi_segments'(Cs, Segs),
    '$swi_resolve'(Segs, [], Rev),
    lists:reverse(Rev, Kept),
    '$swi_join'(Kept, Path).
'$swi_segments'(Cs, [S|Ss]) :-
    '$swi_upto_sep'(Cs, ['/'], S, Rest),
    ( Rest = [_|After] -> '$swi_segments'(After, Ss) ; Ss = [] ).
'$swi_resolve'([], Acc, Acc).
'$swi_resolve'([S|Ss], Acc0, Acc) :-
    (   ( S == [] ; S == ['.'] ) -> Acc1 = Acc0
    ;   S == ['.', '.'] -> ( Acc0 = [_|Acc1] -> true ; Acc1 = [] )
    ;   Acc1 = [S|Acc0]
    ),
    '$swi_resolve'(Ss, Acc1, Acc).
'$swi_join'([], ['/']).
'$swi_join'([S], ['/'|S]) :- !.
'$swi_join'([S|Ss], Path) :-
    '$swi_join'(Ss, Rest),
    '$sitlog_append'(['/'|S], Rest, Path).

% ------------------------------------------------------------- time

% dynamic(Specs) as a goal: an application's `:- dynamic foo/1.` is run
% as a goal, under the call's limits, and the engine has no such
% predicate. Each Name/Arity (in a list or a conjunction) becomes a
% dynamic predicate with no clauses; one that is dynamic already (an
% application's predicates are asserted) is left as it is.
'$swi_dynamic'(S) :-
    var(S),
    !,
    throw(error(instantiation_error, dynamic/1)).
'$swi_dynamic'([]) :- !.
'$swi_dynamic'([S|Ss]) :- !, '$swi_dynamic'(S), '$swi_dynamic'(Ss).
'$swi_dynamic'((A, B)) :- !, '$swi_dynamic'(A), '$swi_dynamic'(B).
'$swi_dynamic'(_:S) :- !, '$swi_dynamic'(S).
'$swi_dynamic'(N/A) :-
    atom(N),
    integer(A),
    !,
    functor(H, N, A),
    '$sitlog_lz_touch'(N, A),           % a lazily loaded one: dynamic
    (   catch(predicate_property(H, dynamic), _, fail)
    ->  true
    ;   assertz(H),
        retract(H)
    ).
'$swi_dynamic'(S) :-
    throw(error(type_error(predicate_indicator, S), dynamic/1)).

% Asks the host: `S` requests (time, cputime, walltime, epoch, sleep(T))
% are answered with a number (engine.rs, system_reply).
'$sitlog_system'(Request, Value) :-
    put_char(user_error, '\x1\'),
    put_char(user_error, 'S'),
    write(user_error, Request),
    put_char(user_error, '\x2\'),
    flush_output(user_error),
    get_line_to_chars(user_input, Line, []),
    read_from_chars(Line, Reply),
    (   Reply = '$ok'(V, _) -> Value = V
    ;   Reply = '$error'(E) -> throw(E)
    ;   fail
    ).

% get_time(-Stamp): seconds since the epoch, a float.
'$swi_get_time'(T) :- '$sitlog_system'(time, T).

% sleep(+Seconds).
'$swi_sleep'(T) :-
    (   number(T) -> '$sitlog_system'(sleep(T), _)
    ;   throw(error(type_error(number, T), sleep/1))
    ).

% stamp_date_time(+Stamp, -date(Y,M,D,H,Mn,S,Off,TZ,DST), +TimeZone):
% TimeZone `'UTC'`, an offset in seconds west of UTC, or `local` (taken as
% UTC: the engine knows no time zones).
'$swi_stamp_date_time'(Stamp, date(Y, Mo, D, H, Mn, S, Off, TZ, DST), Zone) :-
    (   Zone == 'UTC' -> Off = 0, TZ = 'UTC', DST = (-)
    ;   Zone == local -> Off = 0, TZ = 'UTC', DST = false
    ;   integer(Zone) -> Off = Zone, TZ = (-), DST = (-)
    ;   throw(error(domain_error(timezone, Zone), stamp_date_time/3))
    ),
    Local is Stamp - Off,
    Days is floor(Local / 86400),
    Secs is Local - Days * 86400,
    '$swi_civil'(Days, Y, Mo, D),
    H is floor(Secs) // 3600,
    Mn is (floor(Secs) mod 3600) // 60,
    S is float(Secs - H * 3600 - Mn * 60).

% date_time_stamp(+date(Y,M,D,H,Mn,S,Off,_,_), -Stamp).
'$swi_date_time_stamp'(date(Y, Mo, D, H, Mn, S, Off, _, _), Stamp) :-
    '$swi_days'(Y, Mo, D, Days),
    ( integer(Off) -> O = Off ; O = 0 ),
    Stamp is float(Days * 86400 + H * 3600 + Mn * 60 + S + O).

% day_of_the_week(+date(Y,M,D), -Day): 1 is Monday, 7 Sunday.
'$swi_day_of_the_week'(Date, W) :-
    arg(1, Date, Y), arg(2, Date, M), arg(3, Date, D),
    '$swi_days'(Y, M, D, Days),
    W is (Days + 3) mod 7 + 1.

% Days since 1970-01-01 of a civil date, and back (H. Hinnant's algorithms).
'$swi_days'(Y0, M, D, Days) :-
    ( M =< 2 -> Y is Y0 - 1 ; Y = Y0 ),
    Era is Y // 400,
    YoE is Y - Era * 400,
    MP is (M + 9) mod 12,
    DoY is (153 * MP + 2) // 5 + D - 1,
    DoE is YoE * 365 + YoE // 4 - YoE // 100 + DoY,
    Days is Era * 146097 + DoE - 719468.
'$swi_civil'(Days, Y, M, D) :-
    Z is Days + 719468,
    Era is Z // 146097,
    DoE is Z - Era * 146097,
    YoE is (DoE - DoE // 1460 + DoE // 36524 - DoE // 146096) // 365,
    Y0 is YoE + Era * 400,
    DoY is DoE - (365 * YoE + YoE // 4 - YoE // 100),
    MP is (5 * DoY + 2) // 153,
    D is DoY - (153 * MP + 2) // 5 + 1,
    M is (MP + 2) mod 12 + 1,
    ( M =< 2 -> Y is Y0 + 1 ; Y = Y0 ).

% statistics(+Key, -Value): runtime, cputime, process_cputime, walltime,
% real_time, inferences (not counted: 0), epoch.
'$swi_statistics'(K, V) :-
    (   K == runtime -> '$swi_stat_ms'(cputime, K, V)
    ;   K == process_cputime -> '$sitlog_system'(cputime, V)
    ;   K == cputime -> '$sitlog_system'(cputime, V)
    ;   K == walltime -> '$swi_stat_ms'(walltime, K, V)
    ;   K == real_time -> '$sitlog_system'(walltime, W),
        T is W // 1000, '$swi_since'(K, T, D), V = [T, D]
    ;   K == inferences -> V = 0
    ;   K == epoch -> '$sitlog_system'(epoch, V)
    ;   throw(error(domain_error(statistics_key, K), statistics/2))
    ).
'$swi_stat_ms'(What, K, [T, D]) :-
    '$sitlog_system'(What, X),
    ( What == cputime -> T is round(X * 1000) ; T = X ),
    '$swi_since'(K, T, D).
'$swi_since'(K, T, D) :-
    atom_concat('$swi_stat_', K, Key),
    ( catch(bb_get(Key, T0), _, fail) -> true ; T0 = 0 ),
    D is T - T0,
    bb_put(Key, T).
