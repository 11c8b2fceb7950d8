left ==> none.
right ==> kept.
