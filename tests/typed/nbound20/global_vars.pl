case ==> plain.
