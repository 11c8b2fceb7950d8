% Helper review19 (issue 37, shape d): a neutral chain of three situations
% per element. `audit(Rounds, Boxes, Label)` calls `scan(Boxes, Label)`
% each round; each box goes through `box([B|Bs])`, `label(B, Bs)` and
% `skip(Bs)` until a box equals the label (`match(B)`) or none is left.
diag_mod(audit(Rounds, Boxes, Label),
  [ [ id ==> round,
      type ==> recursive,
      embedded_dm ==> scan(Boxes, Label),
      arcs ==> [ match(_B) : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round),
                 nomatch : [inc(done, N)] => (N >= Rounds -> stop ; otherwise -> round) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(scan(Boxes, Label),
  [ [ id ==> open,
      type ==> neutral,
      arcs ==> [ empty : empty => box(Boxes) ]
    ],
    [ id ==> box([]),
      type ==> neutral,
      arcs ==> [ empty : empty => nomatch ]
    ],
    [ id ==> box([B|Bs]),
      type ==> neutral,
      arcs ==> [ empty : empty => label(B, Bs) ]
    ],
    [ id ==> label(B, Bs),
      type ==> neutral,
      arcs ==> [ empty : empty => (B == Label -> match(B) ; otherwise -> skip(Bs)) ]
    ],
    [ id ==> skip(Bs),
      type ==> neutral,
      arcs ==> [ empty : empty => box(Bs) ]
    ],
    [ id ==> match(B), type ==> final ],
    [ id ==> nomatch, type ==> final ]
  ],
  []
).
