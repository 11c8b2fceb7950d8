% The behaviour library's language functions: what the robot understands
% of an utterance (a small grammar of dialogue acts) and how it names the
% things it talks about. Written for sitlog-rs; applications
% consult this file from their user_functions.pl:
%
%     :- consult('behaviors/language.pl').
%
% Understanding is vocabulary-driven, not a match on fixed sentences: the
% caller passes what the robot knows of the world,
%
%     vocab(Names, Objects, Classes)
%
% Names are words to ignore when addressed (the robot's and the user's
% names), Objects the individuals it can talk about, Classes the classes.
% An utterance becomes a list of dialogue acts:
%
%     yes, no                      polarity ("yes golem please", "no thanks")
%     done                         nothing more ("that is ok", "that's all")
%     mood(good) / mood(bad)       "i had a bad day", "great"
%     order(Items)                 "bring me something to drink and biscuits"
%     like(Item)                   "i like malz", "i like noodles best"
%     accept(Item)                 "noodles are ok", "the coke is fine"
%     mention(Item)                an item named on its own ("malz")
%
% and Item is object(O), class(C) or unknown(Word). Words are compared in
% lower case; a plural or singular form of an object's name also names it
% ("biscuit", "cokes").

% ------------------------------------------------------------------ words

% utterance_words(+Text, -Words): the lower-case words of an atom.
utterance_words(Text, Words) :-
    atom_codes(Text, Codes),
    lang_split(Codes, [], Words).

lang_split([], Acc, Words) :-
    lang_flush(Acc, [], Words).
lang_split([C|Cs], Acc, Words) :-
    (   lang_word_code(C, L)
    ->  lang_split(Cs, [L|Acc], Words)
    ;   C =:= 0'\'
    ->  lang_split(Cs, Acc, Words)
    ;   lang_flush(Acc, Rest, Words),
        lang_split(Cs, [], Rest)
    ).

lang_flush([], Rest, Rest).
lang_flush([C|Cs], Rest, [W|Rest]) :-
    lang_reverse([C|Cs], [], Codes),
    atom_codes(W, Codes).

lang_word_code(C, L) :-
    (   C >= 0'A, C =< 0'Z
    ->  L is C + 32
    ;   C >= 0'a, C =< 0'z
    ->  L = C
    ;   C >= 0'0, C =< 0'9
    ->  L = C
    ;   C =:= 0'_
    ->  L = C
    ).

lang_reverse([], Acc, Acc).
lang_reverse([X|Xs], Acc, R) :-
    lang_reverse(Xs, [X|Acc], R).

% lang_member(+X, +List): X is in List (once). lang_in/2 enumerates.
lang_member(X, [X|_]) :- !.
lang_member(X, [_|Xs]) :-
    lang_member(X, Xs).

lang_in(X, [X|_]).
lang_in(X, [_|Xs]) :-
    lang_in(X, Xs).

lang_append([], Ys, Ys).
lang_append([X|Xs], Ys, [X|Zs]) :-
    lang_append(Xs, Ys, Zs).

% Words that carry no content in a request.
lang_filler(W) :-
    lang_member(W, [hi, hello, hey, please, thanks, thank, you, well, oh,
                    um, uh, dear, just, really, then, so]).

lang_determiner(W) :-
    lang_member(W, [the, a, an, some, my, me, us, of, any, your, more]).

lang_yes(W) :- lang_member(W, [yes, yeah, yep, sure, certainly, right, okay, alright]).
lang_no(W) :- lang_member(W, [no, nope, nah, not]).

lang_fine(W) :- lang_member(W, [ok, okay, fine, good, great, alright]).

% Verbs of a request, and what "something to V" asks for.
lang_request_verb(W) :-
    lang_member(W, [bring, get, fetch, give, want, need, would, like_to]).
lang_verb_class(drink, drink).
lang_verb_class(eat, food).

% --------------------------------------------------------------- the acts

% parse_utterance(+Text, +Vocab): the dialogue acts of Text.
parse_utterance(Text, Vocab) :-
    utterance_acts(Text, Vocab, Acts),
    assign_func_value(Acts).

% utterance_acts(+Text, +Vocab, -Acts)
utterance_acts(Text, vocab(Names, Objects, Classes), Acts) :-
    utterance_words(Text, Words0),
    lang_content(Words0, Names, Words),
    lang_acts(Words, vocab(Names, Objects, Classes), Acts).

% The words without the names and fillers.
lang_content([], _, []).
lang_content([W|Ws], Names, Out) :-
    (   ( lang_member(W, Names) ; lang_filler(W) )
    ->  Out = Rest
    ;   Out = [W|Rest]
    ),
    lang_content(Ws, Names, Rest).

lang_acts(Words, Vocab, Acts) :-
    lang_polarity(Words, Pol, Rest0),
    lang_body(Rest0, Vocab, Body),
    lang_append(Pol, Body, Acts).

% A leading yes or no.
lang_polarity([W|Ws], [yes], Ws) :- lang_yes(W), !.
lang_polarity([W|Ws], [no], Ws) :- lang_no(W), !.
lang_polarity([ok], [yes], []) :- !.
lang_polarity(Ws, [], Ws).

lang_body([], _, []) :- !.
% nothing more: "that is ok", "that's all", "nothing", "it is fine"
lang_body(Ws, _, [done]) :-
    (   Ws = [that|T] ; Ws = [thats|T] ; Ws = [it|T] ; Ws = [its|T] ),
    lang_copula_fine(T),
    !.
lang_body([nothing|_], _, [done]) :- !.
lang_body(Ws, _, [done]) :-
    ( lang_append(_, [thats, all], Ws) ; lang_append(_, [that, is, all], Ws) ),
    !.
% the day
lang_body(Ws, _, [mood(M)]) :-
    lang_mood(Ws, M),
    !.
% a request
lang_body(Ws, Vocab, [order(Items)]) :-
    lang_append(_, [V|After], Ws),
    lang_request_verb(V),
    lang_items(After, Vocab, Items),
    Items \== [],
    !.
% a preference
lang_body(Ws, Vocab, [like(Item)]) :-
    (   lang_append(_, [like|After], Ws)
    ;   lang_append(_, [prefer|After], Ws)
    ;   lang_append(_, [love|After], Ws)
    ;   lang_append(_, [choose|After], Ws)
    ),
    lang_items(After, Vocab, [Item|_]),
    !.
% an acceptance: "noodles are ok", "the coke is fine"
lang_body(Ws, Vocab, [accept(Item)]) :-
    lang_append(Before, [Be|Fine], Ws),
    lang_member(Be, [is, are]),
    lang_copula_fine([Be|Fine]),
    lang_items(Before, Vocab, [Item|_]),
    !.
% items on their own
lang_body(Ws, Vocab, Acts) :-
    lang_items(Ws, Vocab, Items),
    Items \== [],
    lang_mentions(Items, Acts),
    !.
lang_body(_, _, []).

lang_copula_fine([Be|T]) :-
    lang_member(Be, [is, are, s, will, would]),
    !,
    lang_copula_fine(T).
lang_copula_fine([be|T]) :- !, lang_copula_fine(T).
lang_copula_fine([W|_]) :- lang_fine(W).
lang_copula_fine([all]).

lang_mentions([], []).
lang_mentions([I|Is], [mention(I)|Ms]) :- lang_mentions(Is, Ms).

lang_mood(Ws, bad) :-
    (   lang_append(_, [bad|_], Ws)
    ;   lang_append(_, [terrible|_], Ws)
    ;   lang_append(_, [awful|_], Ws)
    ;   lang_append(_, [tired|_], Ws)
    ;   lang_append(_, [hard|_], Ws)
    ),
    !.
lang_mood(Ws, good) :-
    lang_append(_, [day|_], Ws),
    (   lang_append(_, [good|_], Ws)
    ;   lang_append(_, [great|_], Ws)
    ;   lang_append(_, [nice|_], Ws)
    ;   lang_append(_, [fine|_], Ws)
    ),
    !.

% lang_items(+Words, +Vocab, -Items): the items of a phrase, split at
% "and" and commas (commas are gone already), in order.
lang_items(Words, Vocab, Items) :-
    lang_chunks(Words, [], Chunks),
    lang_chunk_items(Chunks, Vocab, Items).

lang_chunks([], [], []) :- !.
lang_chunks([], Acc, [Chunk]) :-
    lang_reverse(Acc, [], Chunk).
lang_chunks([W|Ws], Acc, Chunks) :-
    (   lang_member(W, [and, or, with, plus, also])
    ->  (   Acc == []
        ->  Chunks = Rest
        ;   lang_reverse(Acc, [], Chunk),
            Chunks = [Chunk|Rest]
        ),
        lang_chunks(Ws, [], Rest)
    ;   lang_chunks(Ws, [W|Acc], Chunks)
    ).

lang_chunk_items([], _, []).
lang_chunk_items([C|Cs], Vocab, Items) :-
    (   lang_chunk_item(C, Vocab, I)
    ->  Items = [I|Rest]
    ;   Items = Rest
    ),
    lang_chunk_items(Cs, Vocab, Rest).

% "something to drink", "anything to eat"
lang_chunk_item(Ws, vocab(_, _, Classes), class(C)) :-
    lang_append(_, [to, V|_], Ws),
    lang_verb_class(V, C),
    lang_member(C, Classes),
    !.
% a word naming an object or a class (the last one wins: "the malz bottle"
% is not understood, "a bottle of malz" is)
lang_chunk_item(Ws, Vocab, Item) :-
    lang_reverse(Ws, [], Rev),
    lang_named(Rev, Vocab, Item),
    !.

lang_named([W|_], Vocab, Item) :-
    lang_word_item(W, Vocab, Item),
    !.
lang_named([_|Ws], Vocab, Item) :-
    lang_named(Ws, Vocab, Item).

lang_word_item(W, vocab(_, Objects, _), object(O)) :-
    lang_in(O, Objects),
    lang_same_noun(W, O),
    !.
lang_word_item(W, vocab(_, _, Classes), class(C)) :-
    lang_in(C, Classes),
    lang_same_noun(W, C),
    !.
lang_word_item(W, _, unknown(W)) :-
    \+ lang_determiner(W),
    \+ lang_member(W, [something, anything, i, it, is, are, to, best, better,
                       more, too, also, bring, get, want, like, please,
                       ok, fine, okay, good]).

% W names N: the same word, or one is the other plus "s" or "es".
lang_same_noun(W, W) :- !.
lang_same_noun(W, N) :-
    atom_codes(W, Wc),
    atom_codes(N, Nc),
    (   lang_append(Nc, "s", Wc)
    ;   lang_append(Wc, "s", Nc)
    ;   lang_append(Nc, "es", Wc)
    ;   lang_append(Wc, "es", Nc)
    ),
    !.

% ----------------------------------------------------- reading the acts

% acts_answer(+Acts, +Kind): what the acts say in answer to a question of
% Kind, or `not_understood`:
%   yes_no     -> yes | no
%   choice(Os) -> one of Os (liked, accepted or mentioned)
%   order      -> order(Items)
%   mood       -> good | bad
%   more       -> yes | no (no, or nothing more)
%   request    -> order(Items) | no
%   offer(A, B) -> A or B: the one named, else A for yes and B for no
%                  ("shall I bring you A?", B being the alternative)
%   any        -> the acts themselves
acts_answer(Acts, Kind) :-
    (   lang_answer(Kind, Acts, A)
    ->  true
    ;   A = not_understood
    ),
    assign_func_value(A).

lang_answer(yes_no, Acts, yes) :- lang_member(yes, Acts), !.
lang_answer(yes_no, Acts, no) :- lang_member(no, Acts), !.
lang_answer(yes_no, Acts, yes) :- lang_member(done, Acts), !.
lang_answer(choice(Os), Acts, O) :-
    lang_in(Act, Acts),
    lang_item_act(Act, object(O)),
    lang_member(O, Os),
    !.
lang_answer(order, Acts, order(Items)) :-
    lang_member(order(Items), Acts),
    !.
% Items named without a request verb make an order only if one of them is
% known: words the robot cannot place are no order ("lude bu vozeda").
lang_answer(order, Acts, order(Items)) :-
    lang_mentioned(Acts, Items),
    lang_in(Known, Items),
    Known \= unknown(_),
    !.
lang_answer(mood, Acts, M) :- lang_member(mood(M), Acts), !.
lang_answer(more, Acts, no) :- lang_member(no, Acts), !.
lang_answer(more, Acts, no) :- lang_member(done, Acts), !.
lang_answer(more, Acts, yes) :- lang_member(yes, Acts), !.
lang_answer(request, Acts, order(Items)) :-
    lang_answer(order, Acts, order(Items)),
    !.
lang_answer(request, Acts, no) :- lang_member(no, Acts), !.
lang_answer(request, Acts, no) :- lang_member(done, Acts), !.
lang_answer(offer(Asked, Other), Acts, X) :-
    lang_answer(choice([Asked, Other]), Acts, X),
    !.
lang_answer(offer(Asked, _), Acts, Asked) :- lang_member(yes, Acts), !.
lang_answer(offer(_, Other), Acts, Other) :- lang_member(no, Acts), !.
lang_answer(any, Acts, Acts).

lang_item_act(like(I), I).
lang_item_act(accept(I), I).
lang_item_act(mention(I), I).
lang_item_act(order([I|_]), I).

lang_mentioned([], []).
lang_mentioned([mention(I)|As], [I|Is]) :- !, lang_mentioned(As, Is).
lang_mentioned([_|As], Is) :- lang_mentioned(As, Is).

% lang_codes(+X, -Codes): the codes of an atom or number.
lang_codes(P, Codes) :-
    (   atom(P)
    ->  atom_codes(P, C0),
        lang_unscore(C0, Codes)
    ;   number(P)
    ->  number_codes(P, Codes)
    ;   Codes = "?"
    ).

% Identifiers are said with spaces: living_room -> living room.
lang_unscore([], []).
lang_unscore([0'_|Cs], [32|Ds]) :- !, lang_unscore(Cs, Ds).
lang_unscore([C|Cs], [C|Ds]) :- lang_unscore(Cs, Ds).

% ------------------------------------------------------------ sentences

% `say([...])` writes a list by the original's rule (its msg_format/2, in
% test mode and on the robot alike): a space before every element, and a
% final `.` from three elements on. A sentence whose punctuation follows a
% value, or a question, is made into one atom first:
% `say(apply(words(_), [['Which', C, 'would you like?']]))`.

% words(+Words): Words as one sentence, an atom: a space between two words
% but before one that starts with , ; : . ? or !, nested lists spliced in,
% underscores said as spaces, the first letter a capital.
words(Ws) :-
    lang_join(Ws, Codes0),
    lang_capital(Codes0, Codes),
    atom_codes(A, Codes),
    assign_func_value(A).

% lang_words(+Words, -Atom): as words/1, the first letter as it is.
lang_words(Ws, A) :-
    lang_join(Ws, Codes),
    atom_codes(A, Codes).

lang_join(Ws, Codes) :-
    lang_flat(Ws, Fs, []),
    lang_glue(Fs, first, Codes).

lang_flat([], Fs, Fs) :- !.
lang_flat([W|Ws], Fs0, Fs) :- !,
    lang_flat(W, Fs0, Fs1),
    lang_flat(Ws, Fs1, Fs).
lang_flat(W, [W|Fs], Fs).

lang_glue([], _, []).
lang_glue([W|Ws], Pos, Codes) :-
    lang_codes(W, C),
    lang_glue(Ws, next, Rest),
    (   C == []
    ->  Codes = Rest
    ;   Pos == first
    ->  lang_append(C, Rest, Codes)
    ;   C = [P|_], lang_punct(P)
    ->  lang_append(C, Rest, Codes)
    ;   lang_append([32|C], Rest, Codes)
    ).

lang_punct(44).
lang_punct(59).
lang_punct(58).
lang_punct(46).
lang_punct(63).
lang_punct(33).

lang_capital([C|Cs], [U|Cs]) :-
    C >= 97, C =< 122, !,
    U is C - 32.
lang_capital(Cs, Cs).

% ------------------------------------------------------- naming things

% The behaviours speak of a thing by the application's global variables
% `names` (a list of Id-Words, e.g. shelf_food-'the shelf of food') and
% `plurals` (the ids named in the plural), when it declares them.

% name_of(+Id): how the robot says Id: its entry in `names`, else "the "
% and the id with spaces for underscores.
name_of(Id) :-
    (   catch(var_op(get(names, Names)), _, fail),
        lang_lookup(Id, Names, Words)
    ->  true
    ;   lang_codes(Id, Codes),
        lang_append("the ", Codes, All),
        atom_codes(Words, All)
    ),
    assign_func_value(Words).

% is_are(+Id): `are` for a thing named in the plural, else `is`.
is_are(Id) :-
    (   catch(var_op(get(plurals, Ps)), _, fail),
        lang_member(Id, Ps)
    ->  V = are
    ;   V = is
    ),
    assign_func_value(V).

lang_lookup(Id, [K-V|_], V) :- K == Id, !.
lang_lookup(Id, [_|Ps], V) :- lang_lookup(Id, Ps, V).

% names_from(+Pairs): Id-Words pairs from the KB's answers `Id:Words`
% (property_extension(name, L)), dropping unknown ones.
names_from(Pairs) :-
    lang_pairs(Pairs, Names),
    assign_func_value(Names).

lang_pairs([], []).
lang_pairs([Id:W|Ps], [Id-W|Ns]) :- W \== unknown, !, lang_pairs(Ps, Ns).
lang_pairs([_|Ps], Ns) :- lang_pairs(Ps, Ns).

% yes_keys(+Pairs): the ids whose answer is `yes` (property_extension(plural, L)).
yes_keys(Pairs) :-
    lang_yes_keys(Pairs, Ks),
    assign_func_value(Ks).

lang_yes_keys([], []).
lang_yes_keys([K:yes|Ps], [K|Ks]) :- !, lang_yes_keys(Ps, Ks).
lang_yes_keys([_|Ps], Ks) :- lang_yes_keys(Ps, Ks).
