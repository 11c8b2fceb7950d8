% Arithmetic on a variable nothing binds (the engineer forgot the prog).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [Next is Count + 1, say(Next)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
