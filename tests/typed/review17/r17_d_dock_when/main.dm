% review17 (issue 37, shape d): `fleet(Target, Rounds, Docks)` sends a
% robot to find a dock, `Rounds` times. The search takes its arguments the
% other way round (`seek(Want, Among)`), walks `probe([D|Rest])` with a
% `when/3` in the next situation, and ends in `at(D)` or `missing`; the
% caller's exit arc checks the dock found against its own parameter and
% counts in a local. A round: the call, `begin`, a visit a dock, the final.
diag_mod(fleet(Target, Rounds, Docks),
  [ [ id ==> dispatch,
      type ==> recursive,
      embedded_dm ==> seek(Target, Docks),
      arcs ==> [ at(D) : [inc(done, K)] => ((D == Target, K < Rounds) -> dispatch ; otherwise -> halt),
                 missing : [inc(done, K)] => (K < Rounds -> dispatch ; otherwise -> halt) ]
    ],
    [ id ==> halt, type ==> final ]
  ],
  [ done ==> 0 ]
).

diag_mod(seek(Want, Among),
  [ [ id ==> begin,
      type ==> neutral,
      arcs ==> [ empty : empty => probe(Among) ]
    ],
    [ id ==> probe([]),
      type ==> neutral,
      arcs ==> [ empty : empty => missing ]
    ],
    [ id ==> probe([D|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => apply(when(_, _, _), [D == Want, at(D), probe(Rest)]) ]
    ],
    [ id ==> at(_), type ==> final ],
    [ id ==> missing, type ==> final ]
  ],
  []
).
