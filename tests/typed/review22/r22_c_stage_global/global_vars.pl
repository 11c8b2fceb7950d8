fired ==> 0.
