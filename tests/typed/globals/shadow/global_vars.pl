calls ==> 0.
weight ==> 0.5.
last ==> none.
