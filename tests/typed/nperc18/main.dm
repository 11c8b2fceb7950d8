% nperc18 (issue 37): perceptions chosen with the native frames below kept.
% `main(Goal)` calls `ask(Goal)` (the callee's frame on the native stack),
% which listens: a word, a repeated word `pair(X, X)`, a list of words (a
% list expectation: a second read after an input that meets nothing),
% `stop`. The word heard is compared with the goal and handed back in the
% final's id. `tally(Goal)` does the same with a local counting the words
% (a DM with locals hands its own way). Bad inputs: one that meets no
% expectation (the warning, the unmatched input, `Step::Unmet`), a list
% where a word is expected, the end of the script (an error naming the
% callee).
diag_mod(main(Goal),
  [ [ id ==> go,
      type ==> recursive,
      embedded_dm ==> ask(Goal),
      arcs ==> [ heard(W) : say(W) => go,
                 twice(W) : say([twice, W]) => go,
                 found : empty => counted ]
    ],
    [ id ==> counted,
      type ==> recursive,
      embedded_dm ==> tally(Goal),
      arcs ==> [ tallied(N) : say(N) => stop ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(ask(Goal),
  [ [ id ==> is,
      type ==> speech,
      arcs ==> [ [said(X)] : empty => word(X),
                 said(X) : empty => word(X),
                 pair(X, X) : empty => twice(X),
                 stop : empty => found ]
    ],
    [ id ==> word(W),
      type ==> neutral,
      arcs ==> [ empty : empty => (W == Goal -> found ; otherwise -> heard(W)) ]
    ],
    [ id ==> heard(_), type ==> final ],
    [ id ==> twice(_), type ==> final ],
    [ id ==> found, type ==> final ]
  ],
  []
).

diag_mod(tally(Goal),
  [ [ id ==> is,
      type ==> speech,
      arcs ==> [ said(Goal) : [inc(n, _)] => is,
                 said(_) : [inc(n, _)] => is,
                 stop : empty => done ]
    ],
    [ id ==> done,
      type ==> neutral,
      arcs ==> [ empty : get(n, N) => tallied(N) ]
    ],
    [ id ==> tallied(_), type ==> final ]
  ],
  [ n ==> 0 ]
).
