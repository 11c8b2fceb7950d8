% How many drinks Golem has served in this run.
served ==> 0.
