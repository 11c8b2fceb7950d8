% questions asked, and questions given up on, over the whole run
tries ==> 0.
failures ==> 0.
