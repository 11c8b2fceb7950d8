% A callee that hands its result back through its argument (`diag_mod`),
% the caller saying it in the exit arc: `Total` has a value only after the
% call, which is how SitLog returns results.
diag_mod(main,
  [ [ id ==> count, type ==> recursive,
      embedded_dm ==> tally([1, 2, 3], Total),
      arcs ==> [ done(_) : say(['The total is', Total]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(tally(Items, _Sum),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => add(Items, 0) ] ],
    [ id ==> add([], S), type ==> neutral,
      arcs ==> [ empty : empty => done(S) ] ],
    [ id ==> add([X|Xs], S), type ==> neutral,
      arcs ==> [ empty : empty => add(Xs, S1 is S + X) ] ],
    [ id ==> done(S), type ==> final, diag_mod ==> tally(Items, S) ] ],
  []).
