% Every element of the papers' notation in one small program (for the
% diagram tests): a direct arc, a self-loop, several instances of one
% situation id (a ∨), a conditional and a user function as next
% situation (function dots), a next situation bound by the expectation
% (computed), and a recursive situation whose embedded DM has two final
% situations (return dots).
diag_mod(main,
  [
    [ id ==> is,
      type ==> speech,
      arcs ==> [
        go(N) : empty => count(N),
        again : say(again) => is,
        ask : empty => (get(mode, _M) == fast -> quick ; otherwise -> ask_user),
        pick(X) : empty => apply(choose(_), [X]),
        jump(S) : say(S) => S
      ]
    ],
    [ id ==> count(0),
      type ==> neutral,
      arcs ==> [ empty : say(zero) => quick ]
    ],
    [ id ==> count(N),
      type ==> neutral,
      arcs ==> [ empty : say(N) => count(apply(dec(_), [N])) ]
    ],
    [ id ==> quick,
      type ==> recursive,
      embedded_dm ==> confirm(yes_no),
      arcs ==> [
        yes : empty => done,
        no : say('Again, then.') => is
      ]
    ],
    [ id ==> ask_user,
      type ==> neutral,
      arcs ==> [ empty : say('Asking.') => quick ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  [ mode ==> fast ]
).
