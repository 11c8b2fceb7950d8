% rooms: the places the tour visits.
rooms :- assign_func_value([hall, bath, bed, study, cellar, attic, garage, kitchen]).
