g ==> none.
h ==> none.
k ==> 0.
