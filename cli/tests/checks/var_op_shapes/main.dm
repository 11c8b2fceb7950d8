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

% `set` stores `C + 1` as written (the term `0+1`), then `inc` stops the run
% (E0242: every way to the `inc` sets it so); only in a branch: not reported.
diag_mod(counting,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [get(count, C), set(count, C + 1)] => again ] ],
    [ id ==> again, type ==> neutral,
      arcs ==> [ empty : [inc(count, N), say(N)] => maybe ] ],
    [ id ==> maybe, type ==> neutral,
      arcs ==> [ empty : [get(total, T), (T == 0 -> set(total, T + 1) ; otherwise -> empty)] => last ] ],
    [ id ==> last, type ==> neutral,
      arcs ==> [ empty : [inc(total, M), say(M)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ count ==> 0, total ==> 0 ]).
