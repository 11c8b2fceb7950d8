floor_of(kitchen, 0).
floor_of(bedroom, 1).
room_floor(Room) :- floor_of(Room, F), assign_func_value(F).
