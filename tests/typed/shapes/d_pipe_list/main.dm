% Shape (d): the list comes in the pipe (`--in-arg '[3, 8, 12, 5]'`: the
% command line's, so `ground`), read by the callee's first situation
% (`in_arg ==> Ns`) and walked by `next([N|Rest])` against a goal, ints or
% atoms; the list pattern takes the `ground` value as a list once, the
% walk after it is over a typed list. The caller's rounds a local
% compared with `>=`; exit arcs `at(_)` and a variable.
diag_mod(seek(Times, Goal),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> look(Goal),
      arcs ==> [ at(_) : [inc(done, D)] => (D >= Times -> out ; otherwise -> round),
                 Other : [inc(done, D)] => (D >= Times -> out ; otherwise -> round) ]
    ],
    [ id ==> out, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(look(Goal),
  [ [ id ==> start, type ==> neutral, in_arg ==> Ns,
      arcs ==> [ empty : empty => next(Ns) ] ],
    [ id ==> next([N|Rest]), type ==> neutral,
      arcs ==> [ empty : empty => (N == Goal -> at(N) ; otherwise -> next(Rest)) ] ],
    [ id ==> next([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> at(N), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
