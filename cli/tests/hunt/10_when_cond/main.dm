% Conditionals: a user function when/3 in out_arg, `->` in an action and
% in a next situation, and `->` without `otherwise` (not a conditional).
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      out_arg ==> apply(when(_C, _T, _E), [B > 3, big, small]),
      arcs ==> [ n(B) : [(B > 3 -> say(many) ; otherwise -> say(few))]
                   => (B > 3 -> report ; otherwise -> fs) ] ],
    [ id ==> report, type ==> neutral, in_arg ==> Size,
      arcs ==> [ empty : say((Size == big -> yes ; no)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
