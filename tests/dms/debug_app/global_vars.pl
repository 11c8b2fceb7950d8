asked ==> 0.
