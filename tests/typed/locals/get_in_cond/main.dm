% A local and a global read inside comparisons (`C < get(limit, _)`,
% `get(glim, _) > C`), both set from the DM's parameters, so either may be
% no number (an atom, a float, a compound, an unbound variable): the
% comparison's value or its error, the same in both back ends. The count
% is the pipe; the callee `tick` is a native callee with a local of its
% own that shadows the caller's global name `glim` (D-38). The global
% `mark` set to constants (`set(mark, 5)`, `set(mark, yes)`, `set(mark, 2.5)`).
diag_mod(main(Max, G),
  [ [ id ==> start, type ==> neutral, out_arg ==> 0,
      arcs ==> [ empty : [set(limit, Max), set(glim, G), set(mark, 5)] => count ] ],
    [ id ==> count, type ==> neutral, in_arg ==> C, out_arg ==> D,
      arcs ==> [ empty : [D is C + 1] => (C < get(limit, _) -> count ; otherwise -> call) ] ],
    [ id ==> call, type ==> recursive, embedded_dm ==> tick,
      arcs ==> [ ticked : set(mark, 2.5) => glob ] ],
    [ id ==> glob, type ==> neutral, in_arg ==> C, out_arg ==> D,
      arcs ==> [ empty : [D is C + 1] => (get(glim, _) > C -> glob ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ limit ==> 0 ]
).

diag_mod(tick,
  [ [ id ==> t, type ==> neutral, in_arg ==> C, out_arg ==> C,
      arcs ==> [ empty : set(mark, yes) => (C >= get(glim, _) -> ticked ; otherwise -> ticked) ] ],
    [ id ==> ticked, type ==> final ]
  ],
  [ glim ==> 2 ]
).
