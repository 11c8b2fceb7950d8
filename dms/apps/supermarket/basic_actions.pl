% The robot's basic actions (the simulated robot implements them).
[id ==> say, arity ==> [text], mod ==> speech, break ==> no].
[id ==> message, arity ==> [to, text], mod ==> network, break ==> no].
[id ==> navigate, arity ==> [place, status], mod ==> navigation, break ==> yes].
[id ==> grasp, arity ==> [object, hand, status], mod ==> manipulation, break ==> yes].
[id ==> place, arity ==> [hand, status], mod ==> manipulation, break ==> yes].
[id ==> hand_over, arity ==> [hand, status], mod ==> manipulation, break ==> yes].
[id ==> wait, arity ==> [seconds], mod ==> time, break ==> no].
