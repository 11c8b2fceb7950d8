% record_seen(Seen): what the robot saw (Shelf-Objects pairs, the latest
% first) goes into the KB (last_seen, Appendix B.2) and into the global
% `seen` (Object-Shelf pairs: where each object was seen last).
diag_mod(record_seen(Seen),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => shelves(apply(reversed(_), [Seen])) ]
    ],
    [ id ==> shelves([]),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> shelves([Shelf-Objects|Rest]),
      type ==> neutral,
      arcs ==> [ empty : empty => objects(Shelf, Objects, Rest) ]
    ],
    [ id ==> objects(_, [], Rest),
      type ==> neutral,
      arcs ==> [ empty : empty => shelves(Rest) ]
    ],
    [ id ==> objects(Shelf, [O|Os], Rest),
      type ==> neutral,
      arcs ==> [
        empty : [ apply(change_value_object_property(_, _, _), [O, last_seen, Shelf]),
                  assign(S, apply(put_pair(_, _, _), [O, Shelf, get(seen, _)])),
                  set(seen, S) ] => objects(Shelf, Os, Rest)
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
