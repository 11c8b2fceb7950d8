% Helper review24 (issue 37, shape d): a walk of floats for the first near
% a target, decided by a plain Prolog user function (`near/2`, `close` or
% `far`) tested with `\==` in the next situation's condition; the walk's
% first arc reads the target into a local; the rounds counted by the
% caller's id.
diag_mod(tune(Rounds, Freqs, Target),
  [ [ id ==> power,
      type ==> neutral,
      arcs ==> [ empty : empty => scan(0) ]
    ],
    [ id ==> scan(I),
      type ==> recursive,
      embedded_dm ==> dial(Freqs, Target),
      arcs ==> [ locked(_F) : [J is I + 1] => (J >= Rounds -> off ; otherwise -> scan(J)),
                 static : [J is I + 1] => (J >= Rounds -> off ; otherwise -> scan(J)) ]
    ],
    [ id ==> off, type ==> final ]
  ],
  []
).

diag_mod(dial(Freqs, Target),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : set(want, Target) => next(Freqs) ]
    ],
    [ id ==> next([]),
      type ==> neutral,
      arcs ==> [ empty : empty => static ]
    ],
    [ id ==> next([F|Fs]),
      type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(near(_, _), [F, get(want, _)]) \== far -> locked(F) ; otherwise -> next(Fs)) ]
    ],
    [ id ==> locked(_), type ==> final ],
    [ id ==> static, type ==> final ]
  ],
  [ want ==> 0.0 ]
).
