% Issue 39: shapes of programs the original SitLog runs to their end, each
% with a variable that has no value where it is used. They are warnings
% (W0228): the run prints such a variable as `_G..` and goes on.
diag_mod(main,
  [ % bound only in `prog`, which runs on a copy of the situation
    [ id ==> is, type ==> neutral, prog ==> [assign(N, 3)],
      arcs ==> [ empty : [tick(N)] => pick ] ],
    % bound in one situation, used in the next: each visit has fresh variables
    [ id ==> pick, type ==> neutral,
      arcs ==> [ empty : [Colour = red, say(Colour)] => show ] ],
    [ id ==> show, type ==> neutral, prog ==> [assign(Greeting, hello)],
      arcs ==> [ empty : [colour(Colour), say(Greeting), note(V, _T), round(R)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
