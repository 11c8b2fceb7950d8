% Counting visits with `inc(visits)`, the second argument forgotten
% (`inc(visits, _)`), then saying the count.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(visits), say(get(visits, _))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ visits ==> 0 ]).
