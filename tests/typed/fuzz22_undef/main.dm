% Found by the `run` fuzz target (session 22, plans against templates): a
% `get` or `inc` of a name neither local nor global gives a fresh unbound
% value and leaves its variable as it was (the original runs on so), where
% the variable is first named (`main`, `loop(K)`'s callee) and where it is
% named before (`twice`); beside it a local's `get` takes its variable.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say([a, get(nope, L), L, inc(nada, M), M]) => s(L) ] ],
    [ id ==> s(X), type ==> neutral, arcs ==> [ empty : say([b, X]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(twice,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say([L, get(nope, L), L]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(loop(K),
  [ [ id ==> is, type ==> recursive, embedded_dm ==> count(K),
      arcs ==> [ done(N, V) : say(counted(N, V)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(count(K),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(n, _), say([c, get(nope, V), V])] => (get(n, N) < K -> is ; otherwise -> done(N, V)) ] ],
    [ id ==> done(_, _), type ==> final ] ],
  [ n ==> 0 ]).
