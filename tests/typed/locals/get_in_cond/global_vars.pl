glim ==> 0.
mark ==> none.
