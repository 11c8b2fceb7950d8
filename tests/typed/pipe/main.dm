% The pipe read by typed code (issue 28): a variable in_arg is typed like a
% parameter and checked when the frame is loaded. `main` with in_arg Max
% counts to Max, then looks at the pipe again; `half` compares the pipe
% with a float.
diag_mod(main,
  [ [ id ==> is, type ==> neutral, in_arg ==> Max,
      arcs ==> [ empty : [inc(n, N)] => (N >= Max -> look ; otherwise -> is) ] ],
    [ id ==> look, type ==> neutral,
      arcs ==> [ empty : [beep] => check ] ],
    [ id ==> check, type ==> neutral, in_arg ==> L,
      arcs ==> [ empty : [get(n, N)] => (L > 2 -> fs ; otherwise -> again) ] ],
    [ id ==> again, type ==> neutral, in_arg ==> f(_),
      arcs ==> [ empty : [] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0 ]).

diag_mod(half,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(k, K)] => (K >= 3 -> fs ; otherwise -> test) ] ],
    [ id ==> test, type ==> neutral, in_arg ==> X,
      arcs ==> [ empty : [] => (X =< 1.5 -> fs ; otherwise -> is) ] ],
    [ id ==> fs, type ==> final ] ],
  [ k ==> 0 ]).

% `twice`: a typed `prog` (`B is A * 2 + 1` on the pipe, `B` the out_arg,
% read by the arc) until the pipe passes 10; an overflow runs the situation
% untyped, which reports it.
diag_mod(twice,
  [ [ id ==> is, type ==> neutral, in_arg ==> A, out_arg ==> B,
      prog ==> [B is A * 2 + 1],
      arcs ==> [ empty : empty => (B > 10 -> fs ; otherwise -> is) ] ],
    [ id ==> fs, type ==> final ] ],
  []).
