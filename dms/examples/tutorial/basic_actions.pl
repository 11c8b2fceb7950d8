% The basic actions the task uses.
[id ==> say, arity ==> [text], mod ==> speech, break ==> no].
