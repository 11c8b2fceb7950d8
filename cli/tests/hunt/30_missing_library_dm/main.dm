% A first robot task that goes to the kitchen with the library's `move`,
% whose entry the user deleted from `models` (only 'main.dm' is left).
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say('Going to the kitchen') => go ] ],
    [ id ==> go, type ==> recursive,
      embedded_dm ==> move(kitchen, _),
      arcs ==> [ success : say('I am in the kitchen') => fs,
                 error(_) : say('I could not get there') => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
