% Shape (d): the walk `try([P|Ps])` hands back through the pipe, at every
% place it looks at, whether that place is the target: an out_arg the
% evaluator computes (`apply(when(_, _, _), [P == Target, here, elsewhere])`,
% the runtime's `when/3`, as in Appendix A). The caller's run ends with the
% last place's answer in the pipe.
diag_mod(hunt(Rounds, Places, Target),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> search(Places, Target),
      arcs ==> [ found(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done),
                 not_found : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> done) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(search(Places, Target),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]),
      type ==> neutral,
      out_arg ==> apply(when(_, _, _), [P == Target, here, elsewhere]),
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ]
    ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ]
  ],
  []
).
