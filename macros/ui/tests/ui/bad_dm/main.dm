% a DM with a missing next situation
diag_mod(main,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : hello => nowhere ] ],
    [ id ==> fs, type ==> final ] ],
  []).
