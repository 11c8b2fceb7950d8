diag_mod(sub,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => ok ] ]
    [ id ==> ok, type ==> final ] ],
  []).
