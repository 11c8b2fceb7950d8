% A user function whose body fails for the input given.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ room(R) : say(apply(room_floor(X), [R])) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
