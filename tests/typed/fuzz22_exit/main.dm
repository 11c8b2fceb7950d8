% Found by the `run` fuzz target (session 22, plans against templates): the
% exit arc of a recursive situation whose next situation has no value
% (`=> Next`) or is `empty` ends its DM as any arc's does (docs/guide/
% language.md, "Next"): the main DM ends the task (`u`, `e`), a callee's
% caller takes its first exit arc (`top_u`, `top_e`). `loop_u(K)` does so
% after a native loop of typed locals in its callee, `K` times round.
diag_mod(u,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub,
      arcs ==> [ done : say(back) => Next ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(e,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> sub,
      arcs ==> [ done : say(back) => empty ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(top_u,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> u, out_arg ==> top,
      arcs ==> [ _ : say(top) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(top_e,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> e,
      arcs ==> [ _ : say(top) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(sub,
  [ [ id ==> s, type ==> neutral, arcs ==> [ empty : say(sub) => done ] ],
    [ id ==> done, type ==> final ] ],
  []).

diag_mod(loop_u(K),
  [ [ id ==> is, type ==> recursive, embedded_dm ==> count(K),
      arcs ==> [ done(N) : say(counted(N)) => (N > 2 -> Next ; otherwise -> fs) ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(count(K),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : inc(n, _) => (get(n, N) < K -> is ; otherwise -> done(get(n, _))) ] ],
    [ id ==> done(_), type ==> final ] ],
  [ n ==> 0 ]).
