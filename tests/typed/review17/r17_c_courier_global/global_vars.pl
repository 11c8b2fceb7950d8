trips_done ==> 0.
