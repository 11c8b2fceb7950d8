% Helper review25: `route(Stops)` is the list of stops without `hall`, in
% their order; it fails on an improper list (an error of the call).
route(Stops) :- drop_hall(Stops, R), assign_func_value(R).

drop_hall([], []).
drop_hall([hall|Ps], R) :- !, drop_hall(Ps, R).
drop_hall([P|Ps], [P|R]) :- drop_hall(Ps, R).
