speech ==> pardon.
