% A sub-dialogue that ends with `=> empty` instead of a final situation
% (the engineer read `empty` as "nothing more"), and an arc whose next
% situation is a variable the expectation leaves unbound.
diag_mod(main,
  [ [ id ==> is, type ==> recursive,
      embedded_dm ==> ask,
      arcs ==> [ fs : say(first) => is2, Other : say(other(Other)) => is2 ] ],
    [ id ==> is2, type ==> recursive,
      embedded_dm ==> ask2,
      arcs ==> [ done : say(done) => fs, Other : say(other(Other)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(ask,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(asking) => empty ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(ask2,
  [ [ id ==> is, type ==> speech, arcs ==> [ go(N) : say(asking) => N ] ],
    [ id ==> done, type ==> final ] ],
  []).
