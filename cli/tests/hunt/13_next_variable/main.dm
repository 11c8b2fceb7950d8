% The next situation is a variable the arc leaves unbound (the user meant
% to bind it from the answer): the original takes the first situation whose
% id unifies with it, the first of the DM.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ go(_Where) : say(going) => Next,
                 stop : say(bye) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
