% Helper ncall22: read by the calls (`get(g, _)`), set by the callees.
g ==> nothing.
