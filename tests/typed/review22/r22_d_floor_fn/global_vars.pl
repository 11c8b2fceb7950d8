polls ==> 0.
