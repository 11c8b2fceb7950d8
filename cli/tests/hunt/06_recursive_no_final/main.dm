% The caller handles `ok` and `failed`; the callee ends in `done`.
diag_mod(main,
  [ [ id ==> is, type ==> recursive,
      embedded_dm ==> fetch(cup),
      arcs ==> [ ok : say(got_it) => fs, failed : say(sorry) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(fetch(Obj),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(fetching(Obj)) => done ] ],
    [ id ==> done, type ==> final ] ],
  []).
