% serve(Items): turns 19-27 (Appendix B.2). For each item the robot
% searches the shelves in the order of the item's preferred locations
% (object_property_list(O, loc, L): where it was last seen first), records
% where it saw every object on the way (last_seen in the KB, and the
% global `seen`), and takes it with a free hand (the global `taken` keeps
% where). With both hands full, or nothing more to fetch, it delivers.
diag_mod(serve(Items),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => next(Items) ]
    ],
    % Nothing more to fetch: deliver what it holds, if anything.
    [ id ==> next([]),
      type ==> hands,
      arcs ==> [
        hands(_, _) : empty => deliver([]),
        hands(free, free) : empty => done
      ]
    ],
    % More to fetch: deliver first when both hands are full.
    [ id ==> next([O|Os]),
      type ==> hands,
      arcs ==> [
        hands(_, _) : empty => deliver([O|Os]),
        hands(_, free) : empty => fetch(O, Os),
        hands(free, _) : empty => fetch(O, Os)
      ]
    ],
    [ id ==> fetch(O, Os),
      type ==> neutral,
      arcs ==> [
        empty : [ say(['I will get', the, O]),
                  assign(Shelves, apply(unique(_),
                                        [apply(object_property_list(_, _), [O, loc])])) ]
                => search(O, Shelves, Os)
      ]
    ],
    [ id ==> search(O, Shelves, Os),
      type ==> recursive,
      embedded_dm ==> find(O, Shelves, _, _, _),
      arcs ==> [
        found(Shelf, Seen) : empty => saw(Seen, take(O, Shelf, Os)),
        error(_, Seen) : empty => saw(Seen, next(Os))
      ]
    ],
    [ id ==> saw(Seen, Then),
      type ==> recursive,
      embedded_dm ==> record_seen(Seen),
      arcs ==> [ done : empty => Then ]
    ],
    [ id ==> take(O, Shelf, Os),
      type ==> recursive,
      embedded_dm ==> take(O, _, _),
      arcs ==> [
        success(_) : [ assign(T, apply(put_pair(_, _, _), [O, Shelf, get(taken, _)])),
                       set(taken, T) ] => next(Os),
        error(_, _) : empty => next(Os)
      ]
    ],
    [ id ==> deliver(Rest),
      type ==> recursive,
      embedded_dm ==> deliver_all,
      arcs ==> [
        done : empty => next(Rest),
        error(_) : say('I will keep them until I find you.') => done
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
