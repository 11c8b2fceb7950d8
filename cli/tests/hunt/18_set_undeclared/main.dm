% Remembers the user's name in a global that global_vars.pl does not declare.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ name(N) : [set(user_name, N), say(hi(N))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
