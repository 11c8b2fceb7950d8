% Helper ngauge25 (issue 37, shape d): a float `is` in a next situation's
% argument. A round walks the weights, the running load a float in the
% walk's id (`add(Rest, _ is S + W * 0.5)`), until it passes the cap
% (`over(S)`) or the weights end (`under(S)`).
diag_mod(tally(Rounds, Weights, Cap),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> sum(Weights, Cap),
      arcs ==> [ over(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 under(_) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(sum(Ws, Cap),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => add(Ws, 0.0) ] ],
    [ id ==> add([], S), type ==> neutral, arcs ==> [ empty : empty => under(S) ] ],
    [ id ==> add([W|Rest], S),
      type ==> neutral,
      arcs ==> [ empty : empty => (S > Cap -> over(S) ; otherwise -> add(Rest, _T is S + W * 0.5)) ]
    ],
    [ id ==> over(_), type ==> final ],
    [ id ==> under(_), type ==> final ]
  ],
  []
).
