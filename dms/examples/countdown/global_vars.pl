% how many tick(N) steps were taken over the whole run
ticks ==> 0.
