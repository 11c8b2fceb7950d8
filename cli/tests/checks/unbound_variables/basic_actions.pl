[id ==> say, arity ==> [text], mod ==> speech, break ==> no].
[id ==> navigate, arity ==> [place, status], mod ==> navigation, break ==> yes].
