% visits of the situation `is`
rounds ==> 0.
