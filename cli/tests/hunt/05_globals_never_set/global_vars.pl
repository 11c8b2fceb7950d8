user ==> nobody.
visits ==> 0.
