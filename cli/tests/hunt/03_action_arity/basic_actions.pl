% what this robot can do
[id ==> initSpeech, arity ==> [start], mod ==> start, break ==> no].
[id ==> say, arity ==> [message], mod ==> say, break ==> no].
[id ==> sleep, arity ==> [seconds], mod ==> pause, break ==> no].
[id ==> turn, arity ==> [degrees], mod ==> movement, break ==> no].
