calls ==> 0.
