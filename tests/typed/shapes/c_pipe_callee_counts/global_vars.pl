ticks ==> 0.
