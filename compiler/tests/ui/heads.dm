% Embedded DM calls whose arguments can never match the DM's head (E0234),
% and calls that may (a variable, a computed argument, a conditional with
% one branch that matches): those are not reported.
diag_mod(main(In),
[
  [id ==> is, type ==> neutral, arcs ==> [empty : [] => constant]],
  [id ==> constant, type ==> recursive, embedded_dm ==> callee(1),
   arcs ==> [done : [] => functor]],
  [id ==> functor, type ==> recursive, embedded_dm ==> pair(at(kitchen), [a, b]),
   arcs ==> [done : [] => list]],
  [id ==> list, type ==> recursive, embedded_dm ==> pair(to(kitchen), [a]),
   arcs ==> [done : [] => branches]],
  [id ==> branches, type ==> recursive,
   embedded_dm ==> callee((In == a -> 3 ; otherwise -> 4)),
   arcs ==> [done : [] => variable]],
  [id ==> variable, type ==> recursive, embedded_dm ==> callee(In),
   arcs ==> [done : [] => computed]],
  [id ==> computed, type ==> recursive, embedded_dm ==> callee(get(level, _)),
   arcs ==> [done : [] => one_branch]],
  [id ==> one_branch, type ==> recursive,
   embedded_dm ==> callee((In == a -> 2 ; otherwise -> 1)),
   arcs ==> [done : [] => partial]],
  [id ==> partial, type ==> recursive, embedded_dm ==> pair(to(_), [_|_]),
   arcs ==> [done : [] => fs]],
  [id ==> fs, type ==> final]
],
[level ==> 2]).

diag_mod(callee(2),
[
  [id ==> s1, type ==> neutral, arcs ==> [empty : [] => done]],
  [id ==> done, type ==> final]
],
[]).

diag_mod(pair(to(Place), [First, Second]),
[
  [id ==> s1, type ==> neutral, arcs ==> [empty : [say([Place, First, Second])] => done]],
  [id ==> done, type ==> final]
],
[]).
