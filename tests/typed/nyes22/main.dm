% nyes22 (issue 37): perceptions matched in place. A script's input for a
% `listening` or `nkeyboard` situation is `said(Input)`; compiled code
% matches `Input` against each expectation `said(E)` without building
% `said(Input)` (`Percept::Wrapped`), the last that unifies winning, as the
% interpreter unifies the compound. `main(Goal)`: a yes/no question asked
% until `yes` (an input that meets neither is not understood: the
% situation again), words compared with the goal (a variable expectation,
% the goal a parameter, `said(Goal)` binding an unbound goal), shapes with
% the same functor (a repeated variable, a list, numbers, a bare variable
% expectation that takes the whole `said(..)`, an atom that never meets a
% wrapped input), an `nkeyboard` situation and a `speech` one (its input
% not wrapped).
diag_mod(main(Goal),
  [ [ id ==> ask, type ==> recursive, embedded_dm ==> yes_no,
      arcs ==> [ yes : say(yes) => words,
                 no : say(no) => ask ] ],
    [ id ==> words, type ==> recursive, embedded_dm ==> words(Goal),
      arcs ==> [ heard(W) : say(heard(W)) => words,
                 got : say(got(Goal)) => shapes,
                 stopped : empty => shapes ] ],
    [ id ==> shapes, type ==> recursive, embedded_dm ==> shapes,
      arcs ==> [ again(S) : say(S) => shapes,
                 done : empty => keys ] ],
    [ id ==> keys, type ==> nkeyboard,
      arcs ==> [ said(K) : say(key(K)) => talk,
                 said(esc) : say(escape) => talk ] ],
    [ id ==> talk, type ==> speech,
      arcs ==> [ said(X) : say(talked(X)) => fin,
                 X : say(other(X)) => fin ] ],
    [ id ==> fin, type ==> final ]
  ],
  []
).

diag_mod(yes_no,
  [ [ id ==> q, type ==> listening,
      arcs ==> [ said(yes) : empty => yes,
                 said(no) : empty => no ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

diag_mod(words(Goal),
  [ [ id ==> w, type ==> listening,
      arcs ==> [ said(X) : empty => heard(X),
                 said(Goal) : empty => got,
                 said(stop) : empty => stopped ] ],
    [ id ==> heard(_), type ==> final ],
    [ id ==> got, type ==> final ],
    [ id ==> stopped, type ==> final ]
  ],
  []
).

diag_mod(shapes,
  [ [ id ==> s, type ==> listening,
      arcs ==> [ Any : empty => again(any(Any)),
                 said(p(X, Y)) : empty => again(two(X, Y)),
                 said(p(X, X)) : empty => again(pair(X)),
                 said([H|T]) : empty => again(list(H, T)),
                 said(1) : empty => again(one),
                 said(1.5) : empty => again(half),
                 stop : empty => again(never),
                 said(done) : empty => done ] ],
    [ id ==> again(_), type ==> final ],
    [ id ==> done, type ==> final ]
  ],
  []
).
