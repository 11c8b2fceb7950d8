diag_mod(sub,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => is ] ] ],
  []).
