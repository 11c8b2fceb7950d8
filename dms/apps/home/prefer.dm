% prefer(Class, Best, Others): stores the user's choice in the KB as
% conditional defaults of Class: '-'=>>serve=>Best with weight 1, and each
% of Others with weight 2 (the lower the weight, the more preferred).
diag_mod(prefer(Class, Best, Others),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : apply(add_class_property_preference(_, _, _),
                      [Class, ('-'=>>serve=>Best), 1]) => rest(Others)
      ]
    ],
    [ id ==> rest([]),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> rest([O|Os]),
      type ==> neutral,
      arcs ==> [
        empty : apply(add_class_property_preference(_, _, _),
                      [Class, ('-'=>>serve=>O), 2]) => rest(Os)
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
