% Two speech situations and a recovery protocol for speech (pardon):
% what the diagram links a recovery DM to.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ yes : say('Here we go.') => drink,
                 no : say('Maybe later.') => fs ] ],
    [ id ==> drink, type ==> speech,
      arcs ==> [ tea : say('Tea it is.') => fs,
                 coffee : say('Coffee it is.') => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
