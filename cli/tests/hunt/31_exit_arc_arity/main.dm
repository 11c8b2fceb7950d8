% The caller's exit arc expects `found(Thing, Where)` but the callee's final
% is `found(Thing)`: no exit arc matches the final the callee ends in.
diag_mod(main,
  [ [ id ==> look, type ==> recursive,
      embedded_dm ==> search([table, shelf], cup),
      arcs ==> [ found(T, W) : say([T, is, on, the, W]) => fs,
                 missing : say('No cup') => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).

diag_mod(search(Places, Thing),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => at(Places) ] ],
    [ id ==> at([]), type ==> neutral,
      arcs ==> [ empty : empty => missing ] ],
    [ id ==> at([P|Ps]), type ==> speech,
      arcs ==> [ yes : say([Thing, on, P]) => found(Thing),
                 no : empty => at(Ps) ] ],
    [ id ==> found(_T), type ==> final ],
    [ id ==> missing, type ==> final ] ],
  []).
