% Confirmation with the general arc written last, as in a Prolog `case`:
% the last matching arc wins, so the specific one is never taken.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ confirm(R, R) : say(confirmed(R)) => fs,
                 confirm(_, _) : say(mismatch) => is,
                 yes : say(ok) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
