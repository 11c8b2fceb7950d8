% The general arc first, the specific ones after: each can be taken (the
% last matching arc wins).
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ answer(A) : say(pardon(A)) => is,
                 answer(no) : say(ok) => is,
                 answer(yes) : say(great) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
