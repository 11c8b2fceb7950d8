% Issue 39, session 18 (first-week programs 33-36): `get`, `set` and `inc`
% given another number of arguments than two (E0250: the original stops,
% `Ilegal list of terms`); a pattern, not evaluated, is not reported.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(visits), say(get(visits))] => count ] ],
    [ id ==> count, type ==> neutral,
      arcs ==> [ empty : [set(visits, 1, 2), inc(visits, N), say(N)] => fs ] ],
    [ id ==> get(_), type ==> neutral,
      arcs ==> [ empty : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ visits ==> 0 ]).
