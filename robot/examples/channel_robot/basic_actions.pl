% What the robot of the example can do.
[id ==> navigate, arity ==> [place, status], mod ==> navigation, break ==> yes].
[id ==> say, arity ==> [text], mod ==> speech, break ==> no].
