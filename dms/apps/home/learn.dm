% learn: what the robot needs to talk, from its KB: how to name things
% (the global `names`), which names are plural (`plurals`) and the words
% it understands (`vocab`: the agents' names, the comestible objects and
% their classes).
diag_mod(learn,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [
        empty : [ assign(Pairs, apply(property_extension(_), [name])),
                  assign(Names, apply(names_from(_), [Pairs])),
                  set(names, Names),
                  assign(Plurals, apply(yes_keys(_),
                                        [apply(property_extension(_), [plural])])),
                  set(plurals, Plurals),
                  assign(Vocab, apply(home_vocab(_, _, _, _),
                                      [Pairs,
                                       apply(class_extension(_), [agent]),
                                       apply(class_extension(_), [comestible]),
                                       apply(descendants_of_a_class(_), [comestible])])),
                  set(vocab, Vocab) ] => done
      ]
    ],
    [ id ==> done,
      type ==> final
    ]
  ],
  []
).
