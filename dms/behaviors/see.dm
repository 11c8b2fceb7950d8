% see(Objects, Status): what the robot's camera sees on the shelf in front
% of it: Objects, the names of the objects, left to right (possibly []).
% Status: ok.
diag_mod(see(_Objects, _Status),
  [
    [ id ==> is,
      type ==> vision,
      arcs ==> [ objects(Os) : empty => success(Os) ]
    ],
    [ id ==> success(Os),
      type ==> final,
      diag_mod ==> see(Os, ok)
    ]
  ],
  []
).
