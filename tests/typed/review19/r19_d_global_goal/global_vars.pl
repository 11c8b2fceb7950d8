% Helper review19: the goal of the walk, set by the caller once a task.
goal ==> nothing.
