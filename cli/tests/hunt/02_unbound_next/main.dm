% A patrol: the next waypoint is `goto(Next)` where Next is only bound in
% prog (a copy), so the next situation is goto(_): the situation goto(P)
% is selected with P unbound.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      prog ==> [assign(Next, kitchen)],
      arcs ==> [ empty : say(going) => goto(Next) ] ],
    [ id ==> goto(P), type ==> neutral,
      arcs ==> [ empty : [say(at(P)), P = here] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
