% The basic action of the debugger's test application.
[id ==> say, arity ==> [text], mod ==> speech, break ==> no].
