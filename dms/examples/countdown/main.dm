% countdown: situations with parameters, several situations sharing an
% id (semantics.md D-21), `is` arithmetic and a conditional in an action.
%
% `start` reads count(N) and jumps to tick(N).  Two situations have the id
% tick(...): tick(0) is listed first, so the value tick(0) selects it, and
% any other tick(K) falls through to tick(N) with N bound to K.
diag_mod(main,
  [
    [ id ==> start,
      type ==> speech,
      arcs ==> [
        count(N) : [set(from, N)] => tick(N),
        quit : screen(bye) => done
      ]
    ],
    % the end of the countdown
    [ id ==> tick(0),
      type ==> neutral,
      arcs ==> [
        empty : [get(from, F), liftoff(F)] => done
      ]
    ],
    % one step down; says `more` while there are steps left
    [ id ==> tick(N),
      type ==> neutral,
      prog ==> [inc(steps, _)],
      arcs ==> [
        empty : [M is N - 1, inc(ticks, _),
                 (M > 0 -> say(more) ; otherwise -> say(last))] => tick(M)
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  % local variables
  [ from ==> none,
    steps ==> 0
  ]
).
