a ==> none.
b ==> 0.
