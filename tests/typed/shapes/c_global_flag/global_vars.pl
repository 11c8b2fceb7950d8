done ==> no.
jobs ==> 0.
