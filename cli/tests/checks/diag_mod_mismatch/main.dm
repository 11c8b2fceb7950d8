% A new user's diag_mod (issue 39, session 16): a misspelt DM name, a
% wrong arity and a constant the head never takes stop the run when the
% situation is reached (E0237); a diag_mod that may match is left alone.
diag_mod(main,
  [ [id ==> is, type ==> recursive, embedded_dm ==> fetch(juice, _),
      arcs ==> [done : empty => fs, error(_) : empty => fs]],
    [id ==> fs, type ==> final] ], []).

diag_mod(fetch(Object, _Status),
  [ [id ==> is, type ==> speech,
      arcs ==> [yes : empty => done, no : empty => error(no),
                maybe : empty => odd, later : empty => right]],
    [id ==> done, type ==> final, diag_mod ==> fecth(Object, ok)],
    [id ==> error(E), type ==> final, diag_mod ==> fetch(Object, E, now)],
    [id ==> odd, type ==> final, diag_mod ==> other(Object)],
    [id ==> right, type ==> final, diag_mod ==> fetch(Object, late)] ], []).

diag_mod(only(a),
  [ [id ==> fs, type ==> final, diag_mod ==> only(b)] ], []).
