visits ==> 0.
