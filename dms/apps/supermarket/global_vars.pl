% Globals of the supermarket assistant.
% How the robot names things (Id-Words) and the ids said in the plural.
names ==> [].
plurals ==> [].
% The words it understands: vocab(Names, Objects, Classes), from the KB.
vocab ==> vocab([], [], []).
% The right shelf of every product (Object-Shelf), from the KB's classes.
homes ==> [].
% Previous_Shelves: every shelf seen, with what was on it (Shelf-Objects).
observed ==> [].
% Pending task obligations: misplaced objects to put back, put(O, From, To).
pending ==> [].
% Where the customer waits.
customer_at ==> entrance.
% The cost table of the behaviours for the decision and the plan (§8.2):
% costs(Take, Deliver, SearchUser, PMove, PTake, PDeliver, PSearch), seconds
% and probabilities; moving costs its route at the robot's speed.
costs ==> costs(10, 5, 10, 0.95, 0.9, 0.99, 0.9).
