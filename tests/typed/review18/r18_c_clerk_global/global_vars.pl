served ==> 0.
