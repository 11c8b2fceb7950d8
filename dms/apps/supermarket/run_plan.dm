% run_plan(Plan, Sought): carries out a plan of behaviours (take(O, Shelf),
% place(O, Shelf), deliver(O)). Every look at a shelf has its cognitive
% obligations (observe). An object of a side task that is not there any
% more is dropped with its steps; Sought not there ends the plan with
% missing(Shelf), for the inference cycle.
% Final situations: done, missing(Shelf), error(Status).
diag_mod(run_plan(Plan, Sought),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : empty => next(Plan) ]
    ],
    [ id ==> next([]),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> next([take(X, Shelf)|Rest]),
      type ==> recursive,
      embedded_dm ==> move(Shelf, _),
      arcs ==> [
        success : empty => look(X, Shelf, Rest),
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> next([place(X, Shelf)|Rest]),
      type ==> recursive,
      embedded_dm ==> place(X, Shelf, _),
      arcs ==> [
        success : [ apply(change_value_object_property(_, _, _), [X, loc, Shelf]),
                    apply(rm_object_property(_, _), [X, misplaced]),
                    assign(Pending, apply(drop_pending(_, _), [X, get(pending, _)])),
                    set(pending, Pending),
                    say(['I put the', X, 'back on', apply(name_of(_), [Shelf])]) ]
                  => next(Rest),
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> next([deliver(X)|Rest]),
      type ==> recursive,
      embedded_dm ==> give(X),
      arcs ==> [
        done : apply(change_value_object_property(_, _, _), [X, loc, customer])
               => next(Rest),
        error(E) : empty => error(E)
      ]
    ],
    [ id ==> look(X, Shelf, Rest),
      type ==> recursive,
      embedded_dm ==> see(_, _),
      arcs ==> [ success(Objects) : empty => observe(X, Shelf, Objects, Rest) ]
    ],
    [ id ==> observe(X, Shelf, Objects, Rest),
      type ==> recursive,
      embedded_dm ==> observe(Shelf, Objects, X),
      arcs ==> [
        seen : empty => grab(X, Rest),
        missing : empty => ( X == Sought -> missing(Shelf)
                           ; otherwise -> gone(X, Rest) )
      ]
    ],
    [ id ==> gone(X, Rest),
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Pending, apply(drop_pending(_, _), [X, get(pending, _)])),
                  set(pending, Pending) ]
                => next(apply(drop_steps(_, _), [X, Rest]))
      ]
    ],
    [ id ==> grab(X, Rest),
      type ==> recursive,
      embedded_dm ==> take(X, _, _),
      arcs ==> [
        % In the robot's hand, the object is on no shelf.
        success(_) : apply(change_value_object_property(_, _, _), [X, loc, golem])
                     => next(Rest),
        error(E, _) : empty => error(E)
      ]
    ],
    [ id ==> done,
      type ==> final
    ],
    [ id ==> missing(_),
      type ==> final
    ],
    [ id ==> error(_),
      type ==> final
    ]
  ],
  []
).
