% First-week typos: an attribute name (`in_ar`), an arc's next situation
% in another case (`Fs`), and `embeded_dm`.
diag_mod(main,
  [ [ id ==> is, type ==> neutral, in_ar ==> X,
      arcs ==> [ empty : say(X) => step ] ],
    [ id ==> step, type ==> neutral,
      arcs ==> [ empty : say(step) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
