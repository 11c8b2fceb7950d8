% pardon: the recovery protocol of speech situations.
diag_mod(pardon,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say('Pardon? Please say it again.') => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
