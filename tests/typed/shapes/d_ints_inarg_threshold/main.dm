% Shape (d): a list of integer readings searched for the first above a
% threshold; the threshold comes to the walking DM as its in_arg (the
% pipe, set once by the caller's first situation), not as a parameter,
% and travels in the walk's id (`next([N|Rest], T)`); finals `over(N)`
% and `none`; rounds in the caller's id.
diag_mod(scan(Rounds, Readings, Limit),
  [ [ id ==> start, type ==> neutral, out_arg ==> Limit, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> first_over(Readings),
      arcs ==> [ over(V) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 none : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(first_over(Ns),
  [ [ id ==> begin, type ==> neutral, in_arg ==> T, arcs ==> [ empty : empty => next(Ns, T) ] ],
    [ id ==> next([], _), type ==> neutral, arcs ==> [ empty : empty => none ] ],
    [ id ==> next([N|Rest], T),
      type ==> neutral,
      arcs ==> [ empty : empty => (N > T -> over(N) ; otherwise -> next(Rest, T)) ]
    ],
    [ id ==> over(N), type ==> final ],
    [ id ==> none, type ==> final ]
  ],
  []
).
