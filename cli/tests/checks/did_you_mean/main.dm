% Typos of a situation, a variable and a DM.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : inc(countr, _) => greet ] ],
    [ id ==> greeting, type ==> recursive, embedded_dm ==> ask_nme,
      arcs ==> [ done : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [counter ==> 0]).
