rounds ==> 250.
