% Expectations with open list tails (issue 39's program 07): under
% `--legacy` (`Options::close_list_tails`) they are closed as the
% original's evaluator closes them, `[First|Rest]` expecting `[First]`;
% otherwise `Rest` takes the rest of what is heard.
diag_mod(main,
  [ [ id ==> is, type ==> speech,
      arcs ==> [ [First|Rest] : say(heard(First, Rest)) => fs,
                 go([To|Via]) : say(going(To, Via)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
