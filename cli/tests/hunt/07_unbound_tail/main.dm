% Lists with unbound tails: in an action, in a call, in a pattern.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ [First|Rest] : say(visiting(First, Rest)) => call(First, Rest) ] ],
    [ id ==> call(F, R), type ==> recursive,
      embedded_dm ==> visit([F|R], _),
      arcs ==> [ end : say(end) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(visit([P|Ps], _),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(visit(P, Ps)) => end ] ],
    [ id ==> end, type ==> final ] ],
  []).
