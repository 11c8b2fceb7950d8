% Helpers ncold20, ncold21: set by each task's first DM to its argument.
goal ==> nothing.
other ==> nothing.
