% Helper ncall21: set by `glob/1` and `bad/1` to their argument, by
% `change/1` to `changed`.
g ==> nothing.
