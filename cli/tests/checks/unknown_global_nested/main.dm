% Issue 39, session 18 (first-week program 36): a global declared with `=>`
% for `==>` (W0106), then read. As an argument of data (a list said, a next
% situation's argument) the original runs on with the value unbound
% (W0219); as an action itself it stops (E0219).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(['Battery at', get(battery, _)]) => level(get(battery, _)) ] ],
    [ id ==> level(_), type ==> neutral,
      arcs ==> [ empty : [get(battery, B), say(B), set(battery, 5)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
