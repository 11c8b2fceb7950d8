diag_mod(ask_name,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final ] ],
  []).
