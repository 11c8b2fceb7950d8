% A loop driven by scripted input: every `tick` counts in a local
% variable, `stop` ends the task (one transition per input).
diag_mod(main,
  [ [ id ==> is,
      type ==> speech,
      arcs ==> [ tick : [inc(n, _)] => is,
                 stop : [] => fs ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ n ==> 0 ]
).
