% Helper ncold20: set by each task's first DM to its argument.
goal ==> nothing.
