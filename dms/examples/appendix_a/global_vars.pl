% Global variables of the Appendix A example (Listing A2): how often the
% embedded DM `wait` ended in fs1 and in fs2.
g_count_fs1 ==> 0.
g_count_fs2 ==> 0.
