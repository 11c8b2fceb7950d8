% The embedded DM has no final situation yet.
diag_mod(main,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub,
      arcs ==> [ ok : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
