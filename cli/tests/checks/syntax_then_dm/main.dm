% `sub.dm` has a syntax error: only that error is reported, not "no DM named `sub`".
diag_mod(main,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub,
      arcs ==> [ ok : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
