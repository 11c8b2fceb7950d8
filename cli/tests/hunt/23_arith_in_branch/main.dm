% Arithmetic on a variable without a value, but only in the branch of a
% conditional that this run does not take: not a certain failure.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ more(Flag) : [(Flag == yes -> say(Extra + 1) ; otherwise -> say(none))]
                   => (Flag == yes -> count(Extra) ; otherwise -> fs) ] ],
    [ id ==> count(N), type ==> neutral,
      arcs ==> [ empty : [(N > 0 -> M is N - 1 ; otherwise -> M = 0), say(M)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
