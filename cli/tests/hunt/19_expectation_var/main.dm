% Takes whatever the user says (a bare variable as the expectation).
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ Said : say(you_said(Said)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
