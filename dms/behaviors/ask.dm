% ask(Question, Kind, Vocab, Answer, Status): the robot asks Question (an
% atom or a list of words and names) and listens to the user's answer,
% understood as Kind (see acts_answer/2 in language.pl: yes_no,
% choice(Options), order, mood, more, any) with the words Vocab
% (vocab(Names, Objects, Classes)).
% An answer not understood is a common error: the recovery protocol
% `ask_again` says so and repeats the question, twice at most.
%
% Answer: what was understood (yes, no, one of the options, order(Items),
% good, bad, done, or the acts for `any`). Status: ok, not_understood, or
% no_user (nobody answered). Final situations: success(Answer),
% error(Status).
diag_mod(ask(Question, Kind, Vocab, _Answer, _Status),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : say(Question) => listen(1) ]
    ],
    [ id ==> listen(N),
      type ==> speech,
      arcs ==> [
        nobody : empty => error(no_user),
        said(Text) : empty =>
          understood(apply(acts_answer(_, _),
                           [apply(parse_utterance(_, _), [Text, Vocab]), Kind]), N)
      ]
    ],
    [ id ==> understood(not_understood, 3),
      type ==> neutral,
      arcs ==> [ empty : say('Sorry, I still do not understand you.') => error(not_understood) ]
    ],
    [ id ==> understood(not_understood, N),
      type ==> recursive,
      embedded_dm ==> ask_again(Question),
      arcs ==> [ asked : [M is N + 1] => listen(M) ]
    ],
    [ id ==> understood(Answer, _),
      type ==> neutral,
      arcs ==> [ empty : empty => success(Answer) ]
    ],
    [ id ==> success(Answer),
      type ==> final,
      diag_mod ==> ask(Question, Kind, Vocab, Answer, ok)
    ],
    [ id ==> error(E),
      type ==> final,
      diag_mod ==> ask(Question, Kind, Vocab, none, E)
    ]
  ],
  []
).
