% serve(O): fetch O for the customer (Section 8). Where the KB says O is,
% the plan is the scheme: take it there, bring it. When O is not where it
% was believed to be, the daily-life inference cycle runs:
% 1. diagnosis (shop_diagnose): how the assistant filled the shelves, so
%    where O must be (the closest shelf not seen yet) or that the shop ran
%    out of it;
% 2. decision (shop_decide): O for the customer and, as far as r_max (the
%    KB's time budget) allows, the pending put-back obligations;
% 3. the plan of behaviours, carried out by run_plan, which re-enters the
%    cycle if O is not at its assumed shelf either.
% When the shop ran out of O, the robot offers an object of the same kind
% it has seen. Final situations: done (something was delivered), none.
diag_mod(serve(O),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : assign(Shelf, apply(object_property_value(_, _), [O, loc])) => where(Shelf)
      ]
    ],
    [ id ==> where(unknown),
      type ==> neutral,
      arcs ==> [ empty : empty => infer(apply(shop_place_here, [])) ]
    ],
    [ id ==> where(Shelf),
      type ==> neutral,
      arcs ==> [ empty : empty => plan([take(O, Shelf), deliver(O)]) ]
    ],
    [ id ==> plan(Plan),
      type ==> recursive,
      embedded_dm ==> run_plan(Plan, O),
      arcs ==> [
        done : empty => done,
        missing(Shelf) : empty => infer(Shelf),
        error(_) : say(['Sorry, I could not bring you', the, O]) => none
      ]
    ],
    % 1. Diagnosis.
    [ id ==> infer(Shelf),
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Believed, apply(shelf_contents(_),
                                         [apply(property_extension(_), [loc])])),
                  assign(D, apply(shop_diagnose(_, _, _, _),
                                  [Shelf, get(observed, _), Believed, [O]])) ]
                => diagnosed(D)
      ]
    ],
    [ id ==> diagnosed(diagnosis(Placed, RanOut, _)),
      type ==> neutral,
      arcs ==> [
        empty : empty => ( apply(member_of(_, _), [O, RanOut]) == yes -> ran_out
                         ; otherwise -> assumed(apply(lookup(_, _), [O, Placed])) )
      ]
    ],
    % 2. Decision and 3. plan.
    [ id ==> assumed(Shelf),
      type ==> neutral,
      arcs ==> [
        empty : [ say(['I think that the', O, 'was placed on',
                       apply(name_of(_), [Shelf])]),
                  assign(RMax, apply(object_property_value(_, _), [golem, r_max])),
                  assign(Obligations, apply(cons(_, _), [fetch(O, Shelf), get(pending, _)])),
                  assign(Decision, apply(shop_decide(_, _, _, _),
                                         [Obligations, get(customer_at, _), RMax, get(costs, _)])) ]
                => decided(Decision)
      ]
    ],
    [ id ==> decided(decision(_, _, Plan, _, _)),
      type ==> neutral,
      arcs ==> [ empty : say(apply(plan_words(_), [Plan])) => plan(Plan) ]
    ],
    % The shop ran out of O: tell the manager, offer something else.
    [ id ==> ran_out,
      type ==> neutral,
      arcs ==> [
        empty : [ say(['I am sorry, we ran', 'out of', O]),
                  message(apply(name_of(_), [manager]), ['We ran', 'out of', O]),
                  assign(Kind, apply(mother_of_a_class(_), [apply(class_of_an_object(_), [O])])),
                  assign(Alternative, apply(first_seen(_, _, _),
                                            [apply(objects_of_a_class(_), [Kind]),
                                             get(observed, _), O])) ]
                => alternative(Alternative)
      ]
    ],
    [ id ==> alternative(none),
      type ==> neutral,
      arcs ==> [ empty : empty => none ]
    ],
    [ id ==> alternative(A),
      type ==> recursive,
      embedded_dm ==> ask(apply(words(_), [['Would you like the', A, 'instead?']]), yes_no, get(vocab, _), _, _),
      arcs ==> [
        success(yes) : empty => other(A),
        success(no) : say('Ok.') => none,
        error(_) : empty => none
      ]
    ],
    [ id ==> other(A),
      type ==> recursive,
      embedded_dm ==> serve(A),
      arcs ==> [
        done : empty => done,
        none : empty => none
      ]
    ],
    [ id ==> done,
      type ==> final
    ],
    [ id ==> none,
      type ==> final
    ]
  ],
  []
).
