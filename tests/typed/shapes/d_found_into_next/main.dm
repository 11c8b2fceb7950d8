% Shape (d): the caller binds the place of the callee's final `found(P)`
% into its next situation `seen(P, I)` (a neutral situation that reads it:
% a run that found nothing stops); rounds in the caller's ids.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> seek(Places, Target),
      arcs ==> [ found(P) : empty => seen(P, I),
                 not_found : empty => seen(none, I) ]
    ],
    [ id ==> seen(P, I),
      type ==> neutral,
      arcs ==> [ empty : [J is I + 1] =>
                   (P == none -> stop ; otherwise -> (J < Rounds -> round(J) ; otherwise -> stop)) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(seek(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => walk(Places) ] ],
    [ id ==> walk([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> walk([P|Ps]),
      type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> walk(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
