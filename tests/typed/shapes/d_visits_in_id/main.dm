% Shape (d): the walk counts the places it visits in its id
% (`try(Ps, K)`, `K1 is K + 1` in the arc) and hands the count back in its
% final (`found(K)`, `not_found(K)`); the caller adds it to a total in
% its own id (`round(I, Total)`).
diag_mod(survey(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0, 0) ] ],
    [ id ==> round(I, Total),
      type ==> recursive,
      embedded_dm ==> count_to(Places, Target),
      arcs ==> [ found(K) : [J is I + 1, T is Total + K] =>
                   (J < Rounds -> round(J, T) ; otherwise -> stop),
                 not_found(K) : [J is I + 1, T is Total + K] =>
                   (J < Rounds -> round(J, T) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(count_to(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places, 0) ] ],
    [ id ==> try([], K), type ==> neutral, arcs ==> [ empty : empty => not_found(K) ] ],
    [ id ==> try([P|Ps], K),
      type ==> neutral,
      arcs ==> [ empty : [K1 is K + 1] => (P == Target -> found(K1) ; otherwise -> try(Ps, K1)) ]
    ],
    [ id ==> found(K), type ==> final ],
    [ id ==> not_found(K), type ==> final ]
  ],
  []
).
