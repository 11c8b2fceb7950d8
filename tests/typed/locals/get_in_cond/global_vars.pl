glim ==> 0.
