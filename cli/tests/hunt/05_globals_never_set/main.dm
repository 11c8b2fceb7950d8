% Reads globals that nothing sets (their defaults), then one declared
% nowhere: `get(battery, _)`.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(get(user, _)), say(get(visits, V)), say(V)] => check ] ],
    [ id ==> check, type ==> neutral,
      arcs ==> [ empty : say(get(battery, _)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
