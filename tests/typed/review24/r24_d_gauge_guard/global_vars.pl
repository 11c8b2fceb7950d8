cap ==> 0.
