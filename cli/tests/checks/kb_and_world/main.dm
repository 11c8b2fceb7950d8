% A KB service and a function of the simulated robot, in an application
% with neither a knowledge.kb nor a world.toml: warnings.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [apply(object_property_value(_, _), [pete, lives]),
                          apply(shop_shelves, [])] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
