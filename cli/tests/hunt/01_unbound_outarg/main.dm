% A greeter: the name the user gives travels down the pipe; the out_arg of
% the first situation names a variable nothing binds when `skip` is taken.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      out_arg ==> Name,
      arcs ==> [ name(Name) : say(hello(Name)) => greet,
                 skip : say(ok) => greet ] ],
    [ id ==> greet, type ==> neutral, in_arg ==> Who,
      arcs ==> [ empty : say(welcome(Who)) => fs ] ],
    [ id ==> fs, type ==> final, out_arg ==> Result, diag_mod ==> main ] ],
  []).
