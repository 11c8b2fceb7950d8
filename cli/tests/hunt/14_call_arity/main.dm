% A behaviour called with one argument too few; the original compares the
% name only (D-3), then unifies.
diag_mod(main,
  [ [ id ==> is, type ==> recursive,
      embedded_dm ==> go_to(kitchen),
      arcs ==> [ arrived : say(ok) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(go_to(Place, _Status),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(Place) => arrived ] ],
    [ id ==> arrived, type ==> final ] ],
  []).
