% Globals of the home butler.
% What the robot says things are called (Id-Words), filled from the KB.
names ==> [].
% The ids said in the plural ("the noodles are").
plurals ==> [].
% The words it understands: vocab(Names, Objects, Classes), from the KB.
vocab ==> vocab([], [], []).
% Where it saw each object last (Object-Shelf) and what it took (Object-Shelf).
seen ==> [].
taken ==> [].
% Where it found the user.
user_place ==> living_room.
