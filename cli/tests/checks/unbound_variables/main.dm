% Issue 30's reproductions: a variable used once and never bound (`Guest`),
% one used twice and never bound (`Who`), one bound in another situation
% (`Drink`), an action with too many arguments, a typo of `final`.
% What binds is fine: an expectation, a parameter, a function, the status
% an earlier action reports, a condition.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(['Welcome to the bar,', Guest]), say(Who), say(Who)] => ask ] ],
    [ id ==> ask, type ==> speech,
      arcs ==> [ said(Drink) : say(Drink) => go,
                 nothing : say('Welcome', 'to the bar.') => go ] ],
    [ id ==> go, type ==> neutral,
      arcs ==> [ empty : [navigate(bar, Status), say(Status), say(Drink)] => gone(Status) ] ],
    [ id ==> gone(S), type ==> neutral,
      arcs ==> [ empty : [N = 1, say(N), (S == ok -> say(done) ; otherwise -> say(S))] => fs ] ],
    [ id ==> fs, type ==> fianl ] ],
  []).
