% Shape (d): a list of compound places `place(Name, Floor)` matched by a
% field: the first place on the wanted floor (`=:=`), its name handed
% back by the final `at(Name)`; the floor a parameter of the walking DM.
diag_mod(fetch(Rounds, Places, Floor),
  [ [ id ==> start, type ==> neutral, arcs ==> [ empty : empty => round(0) ] ],
    [ id ==> round(I),
      type ==> recursive,
      embedded_dm ==> on_floor(Places, Floor),
      arcs ==> [ at(P) : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop),
                 nowhere : [J is I + 1] => (J < Rounds -> round(J) ; otherwise -> stop) ]
    ],
    [ id ==> stop, type ==> final ]
  ],
  []
).

diag_mod(on_floor(Places, F),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => look(Places) ] ],
    [ id ==> look([]), type ==> neutral, arcs ==> [ empty : empty => nowhere ] ],
    [ id ==> look([place(Name, Fl)|More]),
      type ==> neutral,
      arcs ==> [ empty : empty => (Fl =:= F -> at(Name) ; otherwise -> look(More)) ]
    ],
    [ id ==> at(Name), type ==> final ],
    [ id ==> nowhere, type ==> final ]
  ],
  []
).
