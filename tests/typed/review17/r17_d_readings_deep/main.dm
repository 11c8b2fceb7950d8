% review17 (issue 37, shape d, on ints): three DMs deep. `monitor` polls a
% sensor `Rounds` times; the sensor calls a scan of its readings that
% ends at the first reading above the limit (`high(R)`) or in `low`; the
% sensor turns them into `alarm(R)` and `calm`, which the monitor counts
% in a local. A round: the two calls, `go`, a visit a reading, two finals.
diag_mod(monitor(Rounds, Readings, Limit),
  [ [ id ==> poll,
      type ==> recursive,
      embedded_dm ==> sensor(Readings, Limit),
      arcs ==> [ alarm(_) : [inc(polls, P)] => (P >= Rounds -> off ; otherwise -> poll),
                 calm : [inc(polls, P)] => (P >= Rounds -> off ; otherwise -> poll) ]
    ],
    [ id ==> off, type ==> final ]
  ],
  [ polls ==> 0 ]
).

diag_mod(sensor(Rs, Lim),
  [ [ id ==> read,
      type ==> recursive,
      embedded_dm ==> scan(Rs, Lim),
      arcs ==> [ high(R) : empty => alarm(R),
                 low : empty => calm ]
    ],
    [ id ==> alarm(_), type ==> final ],
    [ id ==> calm, type ==> final ]
  ],
  []
).

diag_mod(scan(Values, Above),
  [ [ id ==> go,
      type ==> neutral,
      arcs ==> [ empty : empty => chk(Values) ]
    ],
    [ id ==> chk([]),
      type ==> neutral,
      arcs ==> [ empty : empty => low ]
    ],
    [ id ==> chk([R|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => (R > Above -> high(R) ; otherwise -> chk(Rest)) ]
    ],
    [ id ==> high(_), type ==> final ],
    [ id ==> low, type ==> final ]
  ],
  []
).
