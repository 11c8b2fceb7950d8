trips ==> 0.
