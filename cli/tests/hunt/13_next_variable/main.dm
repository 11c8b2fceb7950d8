% The next situation is a variable the arc leaves unbound (the user meant
% to bind it from the answer): the original's unbound next situation
% unifies with `empty`, which ends the DM (here the task) after this arc.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ go(_Where) : say(going) => Next,
                 stop : say(bye) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
