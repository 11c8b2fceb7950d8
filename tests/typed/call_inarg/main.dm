% A recursive situation whose variable in_arg only its call reads (helper
% nwait17; review16's finding 3): the pipe's value kept in the waiting
% variant and given to the callee's frame natively, handed to the
% machine's instance where the waiting frame becomes the machine's.

% The count in the pipe, given to the call with the limit the caller keeps
% in its id; the callee counts and ends by comparing with the limit.
diag_mod(main(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask(Max) ] ],
    [ id ==> ask(Lim), type ==> recursive, in_arg ==> N, embedded_dm ==> count(N, Lim),
      arcs ==> [ more : empty => ask(Lim), done : empty => over ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).

diag_mod(count(N, Lim),
  [ [ id ==> step, type ==> neutral, out_arg ==> M,
      arcs ==> [ empty : [M is N + 1] => (M < Lim -> more ; otherwise -> done) ] ],
    [ id ==> more, type ==> final ],
    [ id ==> done, type ==> final ]
  ],
  []
).

% The callee says the count (the waiting frame made the machine's) and
% hands it back in its final's id too.
diag_mod(said(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask(Max) ] ],
    [ id ==> ask(Lim), type ==> recursive, in_arg ==> N, embedded_dm ==> tell(N, Lim),
      arcs ==> [ more : empty => ask(Lim), done(K) : empty => over(K) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

diag_mod(tell(N, Lim),
  [ [ id ==> step, type ==> neutral, out_arg ==> M,
      arcs ==> [ empty : [M is N + 1, say(M)] => (M < Lim -> more ; otherwise -> done(M)) ] ],
    [ id ==> more, type ==> final ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).

% The in_arg read by the call and by an exit arc.
diag_mod(both(Max),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0, arcs ==> [ empty : empty => ask(Max) ] ],
    [ id ==> ask(Lim), type ==> recursive, in_arg ==> N, embedded_dm ==> count(N, Lim),
      arcs ==> [ more : empty => ask(Lim), done : empty => over(N) ] ],
    [ id ==> over(_), type ==> final ]
  ],
  []
).

% The pipe from the command line (an int, a float, an atom, a compound,
% the largest int: `M is N + 1` overflows).
diag_mod(entry,
  [ [ id ==> ask, type ==> recursive, in_arg ==> N, embedded_dm ==> count(N, 3),
      arcs ==> [ more : empty => ask, done : empty => over ] ],
    [ id ==> over, type ==> final ]
  ],
  []
).
