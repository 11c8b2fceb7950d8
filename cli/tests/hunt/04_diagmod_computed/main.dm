% A counter DM returning its result through its argument with a computed
% diag_mod, and a next situation computed by a conditional.
diag_mod(main,
  [ [ id ==> is, type ==> recursive,
      embedded_dm ==> count(3, R),
      arcs ==> [ done : say(counted(R)) => (R == 3 -> fs ; otherwise -> again) ] ],
    [ id ==> again, type ==> neutral, arcs ==> [ empty : say(again) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(count(N, _),
  [ [ id ==> is, type ==> neutral,
      prog ==> [set(total, N)],
      arcs ==> [ empty : say(N) => done ] ],
    [ id ==> done, type ==> final,
      diag_mod ==> count(N, get(total, _)) ] ],
  [ total ==> 0 ]).
