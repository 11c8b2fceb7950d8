% next_selection: next situations computed at run time (issue 28). Generated
% code and the interpreter's plans select the situation a computed next
% situation names by themselves, as the machine would (semantics.md D-21):
% the first situation, in order, whose id unifies with it. `s(X)` shares
% the DM's parameter, so it is instantiated from its template and may take
% `s(..)` first (the machine selects then); `t(..)` is selected by the
% code, `t([])` before `t([H|T])`; `next` goes to a name kept in a local.
diag_mod(main,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> walk(b),
      arcs ==> [ R : say(R) => again ] ],
    [ id ==> again, type ==> recursive, embedded_dm ==> walk(a),
      arcs ==> [ R : say(R) => next ] ],
    [ id ==> next, type ==> neutral,
      arcs ==> [ empty : get(target, N) => N ] ],
    [ id ==> fs, type ==> final ] ],
  [ target ==> fs ]).

diag_mod(walk(X),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(go) => s(a) ] ],
    [ id ==> s(X), type ==> neutral, arcs ==> [ empty : say(param) => t([1, 2]) ] ],
    [ id ==> s(Y), type ==> neutral, arcs ==> [ empty : say(Y) => t([3]) ] ],
    [ id ==> t([]), type ==> neutral, arcs ==> [ empty : say(empty) => u(X) ] ],
    [ id ==> t([H|T]), type ==> neutral, arcs ==> [ empty : say(H) => t(T) ] ],
    [ id ==> u(_N), type ==> final ] ],
  []).
