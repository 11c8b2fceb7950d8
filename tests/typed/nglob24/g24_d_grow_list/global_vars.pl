seen ==> [].
count ==> 0.
