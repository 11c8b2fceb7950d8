% Session 17 (issue 39): failures that are certain from the text, and arcs
% that are never taken. Arithmetic on a variable without a value (E0238),
% `inc` of a local that is never a number (E0242), an arc that a later
% (perceptual) or earlier (recursive) arc always wins over (W0239).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [Next is Count + 1, say(Next)]
                   => (Level > 20 -> ask ; otherwise -> charge) ] ],
    [ id ==> charge, type ==> neutral,
      arcs ==> [ empty : [inc(tries, T), say(T)] => ask ] ],
    [ id ==> ask, type ==> speech,
      arcs ==> [ confirm(R, R) : say(confirmed(R)) => call,
                 confirm(_, _) : say(mismatch) => ask ] ],
    [ id ==> call, type ==> recursive, embedded_dm ==> sub,
      arcs ==> [ _ : say(any) => fs, done : say(done) => fs ] ],
    % only in a branch that may not be taken: not an error
    [ id ==> maybe, type ==> neutral,
      arcs ==> [ empty : (Flag == yes -> X is Y + 1 ; otherwise -> X = 0) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ level ==> 50, tries ==> none ]).
diag_mod(sub,
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(sub) => done ] ],
    [ id ==> done, type ==> final ] ],
  []).
