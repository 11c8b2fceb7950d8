% Typos in names: a global read as `vist` for `visits`, and a next
% situation `fnal` for `final_words`.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(get(vist, _)) => fnal ] ],
    [ id ==> final_words, type ==> neutral,
      arcs ==> [ empty : say(bye) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
