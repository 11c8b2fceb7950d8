% Next situations, embedded DMs, exit arcs and variables that do not exist.
diag_mod(main,
[
  [id ==> is, type ==> neutral, arcs ==> [empty : [set(counter, 1)] => ask]],
  [id ==> ask, type ==> speech,
   arcs ==> [yes : [inc(count, _)] => call_sub, no : [] => nowhere]],
  [id ==> call_sub, type ==> recursive, embedded_dm ==> sub(X),
   arcs ==> [done : [say(X)] => fs, failed : [] => fs]],
  [id ==> call_other, type ==> recursive, embedded_dm ==> sbu(1, 2),
   arcs ==> [done : [] => fs]],
  [id ==> fs, type ==> final]
],
[counter ==> 0]).

diag_mod(sub(R),
[
  [id ==> s1, type ==> neutral, arcs ==> [empty : [] => done]],
  [id ==> done, type ==> final, diag_mod ==> sub(ok)]
],
[]).
