% The user must say the same room twice to confirm it (the last arc whose
% expectation matches wins, so the specific one comes last).
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ confirm(_, _) : say(mismatch) => is,
                 confirm(R, R) : say(confirmed(R)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
