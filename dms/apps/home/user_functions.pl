% User functions of the home butler (the 2021 SitLog paper, Section 9 and
% Appendix B), written for sitlog-rs. The language functions of the
% behaviour library (understanding utterances, naming things) come first.
% The KB services are not called from here: the DMs call them and pass
% their answers in.

:- consult('behaviors/language.pl').

% home_vocab(+NamePairs, +Agents, +Objects, +Classes): the words the robot
% understands: vocab(Names, Objects, Classes), Names being the words of
% the agents' names (said when addressing, ignored when understanding).
% NamePairs are the KB's Id:Name answers (property_extension(name, L)).
home_vocab(NamePairs, Agents, Objects, Classes) :-
    home_name_words(Agents, NamePairs, Words),
    assign_func_value(vocab(Words, Objects, Classes)).

home_name_words([], _, []).
home_name_words([A|As], Pairs, Words) :-
    (   lang_member(A:Name, Pairs), atom(Name)
    ->  utterance_words(Name, W1)
    ;   W1 = []
    ),
    home_name_words(As, Pairs, W2),
    lang_append(W1, W2, Words).

% unique(+List): the list without repeats, first occurrences kept.
unique(List) :-
    home_unique(List, [], U),
    assign_func_value(U).

home_unique([], _, []).
home_unique([X|Xs], Seen, Out) :-
    (   lang_member(X, Seen)
    ->  Out = Rest
    ;   Out = [X|Rest]
    ),
    home_unique(Xs, [X|Seen], Rest).

% preferred_place(+Locations, +LastSeen): where an object should be, from
% its ordered locations (object_property_list(O, loc, L)) and where it was
% last seen (or unknown): the first location once the one that the
% last_seen default put in is taken out (Appendix B.3: the second of the
% list when last_seen is known).
preferred_place(Locations, LastSeen) :-
    (   LastSeen == unknown
    ->  Rest = Locations
    ;   home_delete_first(LastSeen, Locations, Rest)
    ),
    (   Rest = [P|_]
    ->  true
    ;   P = unknown
    ),
    assign_func_value(P).

home_delete_first(_, [], []).
home_delete_first(X, [Y|Ys], Out) :-
    (   X == Y
    ->  Out = Ys
    ;   Out = [Y|Rest],
        home_delete_first(X, Ys, Rest)
    ).

% things(+Objects): the words "the a, the b and the c".
things(Objects) :-
    home_things(Objects, Words),
    lang_words(Words, Sentence),
    assign_func_value(Sentence).

home_things([], []).
home_things([O], [the, O]) :- !.
home_things([O1, O2], [the, O1, and, the, O2]) :- !.
home_things([O|Os], [the, O, ','|Ws]) :- home_things(Os, Ws).

% explanation_words(+Object, +Explanations): why Object is misplaced, from
% the KB's abductive explanations (explanation_of_individual(O, E)), as
% the words of a sentence.
explanation_words(Object, Explanations) :-
    (   lang_member(misplaced:Why, Explanations)
    ->  home_why(Why, Words0)
    ;   Words0 = [for, a, reason, 'I', do, not, know]
    ),
    assign_func_value(['I think that the explanation for this is that the', Object,
                       was, misplaced, there | Words0]).

home_why(moved_by=>Who, [by, your, Who]) :- !.
home_why(Why, [because, Why]).

% put_pair(+Key, +Value, +Pairs): Pairs with Key-Value, replacing an
% earlier pair of the same key.
put_pair(Key, Value, Pairs) :-
    home_put(Pairs, Key, Value, New),
    assign_func_value(New).

home_put([], K, V, [K-V]).
home_put([K0-V0|Ps], K, V, Out) :-
    (   K0 == K
    ->  Out = [K-V|Ps]
    ;   Out = [K0-V0|Rest],
        home_put(Ps, K, V, Rest)
    ).

% others(+Pairs, +Keys): the pairs whose key is not in Keys.
others(Pairs, Keys) :-
    home_others(Pairs, Keys, Out),
    assign_func_value(Out).

home_others([], _, []).
home_others([K-V|Ps], Keys, Out) :-
    (   lang_member(K, Keys)
    ->  Out = Rest
    ;   Out = [K-V|Rest]
    ),
    home_others(Ps, Keys, Rest).

% keys(+Pairs): the keys of Key-Value pairs.
keys(Pairs) :-
    home_keys(Pairs, Ks),
    assign_func_value(Ks).

home_keys([], []).
home_keys([K-_|Ps], [K|Ks]) :- home_keys(Ps, Ks).

% reversed(+List)
reversed(List) :-
    lang_reverse(List, [], R),
    assign_func_value(R).

% health_remark(+Chosen, +Other, +ChosenHealthy, +OtherHealthy): what the
% robot says of a choice, from what the KB says of both.
health_remark(Chosen, Other, yes, no) :-
    !,
    lang_words(['Excellent!', Chosen, is, much, healthier, than, the, Other, '!'], S),
    assign_func_value(S).
health_remark(Chosen, Other, no, yes) :-
    !,
    lang_words(['Ok, I will recall your choice, although', Other, is, healthier, than, Chosen, '.'], S),
    assign_func_value(S).
health_remark(_, _, _, _) :-
    assign_func_value('Great! I will recall your choice!').
