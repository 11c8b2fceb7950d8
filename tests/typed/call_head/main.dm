% One call with head unification (issue 37): a recursive situation whose
% frame native code hands to the machine (`Cx::wait_template`; typed.rs's
% `HandsOver` does it as native code would) calls as the machine's call
% does, its callee's `diag_mod` head unified with the call (E13).
% `main` calls `callee(1)`, whose head `callee(2)` does not unify: an
% error; `ok` calls `echo(1)`, whose head `echo(N)` takes it. The 1 of
% `main`'s call is computed (a local's value): written as a constant, the
% call is one `check` refuses (E0234), a certain failure.
diag_mod(main,
  [ [ id ==> s0, type ==> recursive, embedded_dm ==> callee(get(one, _)),
      arcs ==> [ fs : back => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [one ==> 1]).

diag_mod(callee(2),
  [ [ id ==> t0, type ==> neutral, arcs ==> [ empty : got(2) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(ok,
  [ [ id ==> s0, type ==> recursive, embedded_dm ==> echo(1),
      arcs ==> [ fs : back => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(echo(N),
  [ [ id ==> t0, type ==> neutral, arcs ==> [ empty : got(N) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
