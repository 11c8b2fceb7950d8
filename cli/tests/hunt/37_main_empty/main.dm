% The main DM ends with `=> empty` (the engineer read `empty` as "the
% end") instead of reaching its final situation.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(hello) => greet(world) ] ],
    [ id ==> greet(W), type ==> neutral,
      arcs ==> [ empty : say(hello(W)) => empty ] ],
    [ id ==> fs, type ==> final ] ],
  []).
