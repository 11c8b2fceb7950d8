% Shape (c): the limit a local, set from the parameter at the start and
% counted down with get/set after each call; `>` against 0; a call with
% one constant argument.
diag_mod(countdown(N),
  [ [ id ==> init,
      type ==> neutral,
      arcs ==> [ empty : [set(left, N)] => work ]
    ],
    [ id ==> work,
      type ==> recursive,
      embedded_dm ==> job(1),
      arcs ==> [ finished : [get(left, L), M is L - 1, set(left, M)] =>
                   (M > 0 -> work ; otherwise -> over) ]
    ],
    [ id ==> over, type ==> final ]
  ],
  [ left ==> 0 ]
).

diag_mod(job(Size),
  [ [ id ==> run, type ==> neutral, arcs ==> [ empty : empty => finished ] ],
    [ id ==> finished, type ==> final ]
  ],
  []
).
