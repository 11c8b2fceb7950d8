% observe(Shelf, Objects, Sought): the cognitive obligations of an
% observation (Section 7): the robot saw Objects on Shelf while looking for
% Sought (or `none`).
% 1. Every object the KB placed on Shelf that is not there (and Sought, if
%    not there: the double exception of Section 8.1) is missing: the KB
%    says so (its loc becomes unknown), the robot says what it sees and
%    does not see, and texts the manager.
% 2. Every object seen whose right shelf is another is misplaced: unless
%    the KB knew, the KB is updated (its loc, `misplaced`), the robot says
%    so, and putting it back becomes a pending task obligation.
% The shelf and what is on it join Previous_Shelves (`observed`).
% Final situations: seen (Sought is here), missing.
diag_mod(observe(Shelf, Objects, Sought),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Believed, apply(believed_on(_, _),
                                         [Shelf, apply(property_extension(_), [loc])])),
                  assign(Missing, apply(missing(_, _, _), [Believed, Objects, Sought])),
                  assign(Misplaced, apply(misplaced(_, _, _), [Objects, Shelf, get(homes, _)])),
                  assign(Observed, apply(put_pair(_, _, _), [Shelf, Objects, get(observed, _)])),
                  set(observed, Observed) ]
                => report(Missing, Misplaced)
      ]
    ],
    [ id ==> report([], Misplaced),
      type ==> neutral,
      arcs ==> [ empty : empty => misplaced(Misplaced) ]
    ],
    [ id ==> report(Missing, Misplaced),
      type ==> neutral,
      arcs ==> [
        empty : ( Objects == []
                -> say(['I do not see', apply(things(_), [Missing]), 'on',
                        apply(name_of(_), [Shelf])])
                ; otherwise
                -> say(apply(words(_), [['I see', apply(things(_), [Objects]), ', but I do not see',
                        apply(things(_), [Missing]), '.']])) )
                => lost(Missing, Misplaced)
      ]
    ],
    [ id ==> lost([], Misplaced),
      type ==> neutral,
      arcs ==> [ empty : empty => misplaced(Misplaced) ]
    ],
    [ id ==> lost([M|Ms], Misplaced),
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Known, apply(object_property_value(_, _), [M, loc])),
                  ( Known == unknown -> empty
                  ; otherwise -> apply(change_value_object_property(_, _, _), [M, loc, unknown]) ),
                  message(apply(name_of(_), [manager]),
                          ['The', M, apply(is_are(_), [M]), 'missing from',
                           apply(name_of(_), [Shelf])]) ]
                => lost(Ms, Misplaced)
      ]
    ],
    [ id ==> misplaced([]),
      type ==> neutral,
      arcs ==> [
        empty : empty => ( apply(member_of(_, _), [Sought, Objects]) == yes -> seen
                         ; otherwise -> missing )
      ]
    ],
    [ id ==> misplaced([X|Xs]),
      type ==> neutral,
      arcs ==> [
        empty : assign(Known, apply(object_property_value(_, _), [X, loc]))
                => known(X, Known, Xs)
      ]
    ],
    [ id ==> known(X, Known, Xs),
      type ==> neutral,
      arcs ==> [
        empty : empty => ( Known == Shelf -> misplaced(Xs) ; otherwise -> note(X, Xs) )
      ]
    ],
    [ id ==> note(X, Xs),
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Home, apply(lookup(_, _), [X, get(homes, _)])),
                  apply(change_value_object_property(_, _, _), [X, loc, Shelf]),
                  apply(add_object_property(_, _, _), [X, misplaced, yes]),
                  say(['The', X, apply(is_are(_), [X]), 'not in the right place: the',
                       X, 'should be on', apply(name_of(_), [Home])]),
                  assign(Pending, apply(add_pending_for(_, _, _),
                                        [put(X, Shelf, Home), get(pending, _), Sought])),
                  set(pending, Pending) ]
                => misplaced(Xs)
      ]
    ],
    [ id ==> seen,
      type ==> final
    ],
    [ id ==> missing,
      type ==> final
    ]
  ],
  []
).
