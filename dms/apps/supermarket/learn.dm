% learn: what the robot needs from its KB to talk and to tidy: how to name
% things (`names`, `plurals`), the words it understands (`vocab`: the
% products and their classes) and the right shelf of every product
% (`homes`: the `loc` of its class).
diag_mod(learn,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Names, apply(names_from(_), [apply(property_extension(_), [name])])),
                  set(names, Names),
                  assign(Plurals, apply(yes_keys(_),
                                        [apply(property_extension(_), [plural])])),
                  set(plurals, Plurals),
                  assign(Vocab, apply(shop_vocab(_, _),
                                      [apply(class_extension(_), [product]),
                                       apply(descendants_of_a_class(_), [product])])),
                  set(vocab, Vocab) ]
                => homes(apply(class_extension(_), [product]))
      ]
    ],
    [ id ==> homes([]),
      type ==> neutral,
      arcs ==> [ empty : empty => done ]
    ],
    [ id ==> homes([O|Os]),
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Home, apply(class_property_value(_, _),
                                     [apply(class_of_an_object(_), [O]), loc])),
                  assign(Homes, apply(put_pair(_, _, _), [O, Home, get(homes, _)])),
                  set(homes, Homes) ] => homes(Os)
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
