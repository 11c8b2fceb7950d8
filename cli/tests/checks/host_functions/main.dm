% `poke/1` is registered in Rust by the host and declared in
% host_functions.pl; `pok` is a typo of it.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [apply(poke(_), [x]), apply(pok(_), [x])] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
