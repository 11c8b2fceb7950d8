visited ==> 0.
