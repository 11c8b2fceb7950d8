% A `get`, `set` or `inc` of a variable that is neither local nor global
% (`battery`, declared nowhere) where its value is data: the original
% SitLog prints that the variable is not defined and runs on with the
% value unbound (issue 39's program 36; docs/guide/checking.md, W0219).
% Each place where the original runs on: an element of a list in an
% action's argument, an argument of a next situation, an out_arg, an
% element of a prog, an argument of an embedded DM's call; the run says
% so once per variable on stderr, and both back ends agree.
diag_mod(main,
  [ [ id ==> is, type ==> neutral, prog ==> [get(battery, _), inc(level, _)],
      arcs ==> [ empty : say(['Battery at', get(battery, _), get(level, L)]) => s2(get(battery, _), L) ] ],
    [ id ==> s2(X, L), type ==> recursive, out_arg ==> reading(set(charge, 5), L),
      embedded_dm ==> sub(get(battery, _), get(level, _)),
      arcs ==> [ done(V) : [say([back, X, V]), tick([inc(ticks, _)])] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ level ==> 3 ]).

% A callee whose locals are typed: its loop runs as native code.
diag_mod(sub(A, B),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say([sub, A, B, get(n, N), get(battery, _)]) => (N < 2 -> more ; otherwise -> out) ] ],
    [ id ==> more, type ==> neutral, prog ==> [inc(n, _)],
      arcs ==> [ empty : say([more, get(n, _)]) => is ] ],
    [ id ==> out, type ==> neutral,
      arcs ==> [ empty : say([out, get(charge, _)]) => done(get(n, _)) ] ],
    [ id ==> done(_), type ==> final ] ],
  [ n ==> 0 ]).
