% Helper ncold20 (issue 37): a global (`goal`, typed `ground`) that each
% task's first DM sets to its argument, read by native code in a DM called
% below it elsewhere than a conditional's condition. Started with an
% argument that is not ground (`_`, `f(_)`, `[a|_]`), the first DM's frame
% runs on terms and stores a value native code cannot hold; the
% interpreter goes on with it, and so must the compiled task.

% A global read nested in a next situation's argument.
diag_mod(nest(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> nest_probe,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(nest_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => show(wrap(get(goal, _))) ] ],
    [ id ==> show(W), type ==> neutral,
      arcs ==> [ empty : empty => seen(W) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

% A global read beside a local's read in a next situation.
diag_mod(pair(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> pair_probe,
      arcs ==> [ seen(W, N) : empty => stop(W, N) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

diag_mod(pair_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => show(get(n, _), get(goal, _)) ] ],
    [ id ==> show(N, W), type ==> neutral,
      arcs ==> [ empty : empty => seen(W, N) ] ],
    [ id ==> seen(_, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

% A global read alone as a next situation's argument.
diag_mod(top(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> top_probe,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(top_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => show(get(goal, _)) ] ],
    [ id ==> show(W), type ==> neutral,
      arcs ==> [ empty : empty => seen(W) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

% A global read in an out_arg.
diag_mod(out(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> out_probe,
      arcs ==> [ seen : empty => after ] ],
    [ id ==> after, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : empty => stop(P) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(out_probe,
  [ [ id ==> begin, type ==> neutral, out_arg ==> wrap(get(goal, _)),
      arcs ==> [ empty : empty => seen ] ],
    [ id ==> seen, type ==> final ]
  ],
  []
).

% A global read as a call's argument.
diag_mod(arg(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> arg_mid,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(arg_mid,
  [ [ id ==> begin, type ==> recursive, embedded_dm ==> arg_leaf(wrap(get(goal, _))),
      arcs ==> [ got(W) : empty => seen(W) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

diag_mod(arg_leaf(W),
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => got(W) ] ],
    [ id ==> got(_), type ==> final ]
  ],
  []
).

% A global read in `when/3`'s condition as a next situation.
diag_mod(pick(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> pick_probe,
      arcs ==> [ yes : empty => stop(yes), no : empty => stop(no) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(pick_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => apply(when(_, _, _), [get(goal, _) == a, yes, no]) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).

% A global read beside a local's `inc` in a next situation, after it
% and before it.
diag_mod(inc(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> inc_probe,
      arcs ==> [ seen(W, N) : empty => stop(W, N) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

diag_mod(inc_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => show(inc(n, _), get(goal, _)) ] ],
    [ id ==> show(N, W), type ==> neutral,
      arcs ==> [ empty : empty => seen(W, N) ] ],
    [ id ==> seen(_, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

diag_mod(inc2(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> inc2_probe,
      arcs ==> [ seen(W, N) : empty => stop(W, N) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

diag_mod(inc2_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => show(get(goal, _), inc(n, _)) ] ],
    [ id ==> show(W, N), type ==> neutral,
      arcs ==> [ empty : empty => seen(W, N) ] ],
    [ id ==> seen(_, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

% Left (native code still stops with an error, `performance.md`): a
% global read by an exit arc's action, by a neutral arc's action, in a
% conditional's condition in a DM with a local.
diag_mod(act(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> act_mid,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(act_mid,
  [ [ id ==> begin, type ==> recursive, embedded_dm ==> act_leaf,
      arcs ==> [ done : [get(goal, G)] => seen(G) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

diag_mod(act_leaf,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final ]
  ],
  []
).

diag_mod(acts(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> acts_probe,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(acts_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [get(goal, G)] => seen(G) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

diag_mod(loc(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> loc_probe,
      arcs ==> [ yes : empty => stop(yes), no : empty => stop(no) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(loc_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [inc(n, _)] => (get(goal, _) == a -> yes ; otherwise -> no) ] ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  [ n ==> 0 ]
).

% Helper ncold21: more of the above. A global read in an exit arc's
% action after an `inc` and before one (the `inc` before it not done
% again, the one after it the machine's), in a neutral arc's action
% between a local's `inc` and `set`, read again by the next situation.
diag_mod(act2(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> act2_mid,
      arcs ==> [ seen(W, N, M) : empty => stop(W, N, M) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

diag_mod(act2_mid,
  [ [ id ==> begin, type ==> recursive, embedded_dm ==> act_leaf,
      arcs ==> [ done : [inc(n, N), get(goal, G), inc(n, M)] => seen(G, N, M) ] ],
    [ id ==> seen(_, _, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

diag_mod(acts2(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> acts2_probe,
      arcs ==> [ seen(W, N, M) : empty => stop(W, N, M) ] ],
    [ id ==> stop(_, _, _), type ==> final ]
  ],
  []
).

diag_mod(acts2_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : [inc(n, N), get(goal, G), set(n, 7)] => seen(G, N, get(n, _)) ] ],
    [ id ==> seen(_, _, _), type ==> final ]
  ],
  [ n ==> 3 ]
).

% A global read in an exit arc's action whose arc sets the pipe.
diag_mod(act3(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> act3_mid,
      arcs ==> [ seen(W) : empty => after ] ],
    [ id ==> after, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : empty => stop(P) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(act3_mid,
  [ [ id ==> begin, type ==> recursive, embedded_dm ==> act_leaf,
      out_arg ==> wrap(get(goal, _)),
      arcs ==> [ done : [get(goal, G)] => seen(G) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).

% A global read in an out_arg that also `inc`s, before the read and
% after it.
diag_mod(outinc(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> outinc_probe,
      arcs ==> [ seen : empty => after ] ],
    [ id ==> after, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : empty => stop(P) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(outinc_probe,
  [ [ id ==> begin, type ==> neutral, out_arg ==> f(inc(n, _), get(goal, _)),
      arcs ==> [ empty : empty => mid ] ],
    [ id ==> mid, type ==> neutral, out_arg ==> g(get(goal, _), inc(n, _)),
      arcs ==> [ empty : empty => seen ] ],
    [ id ==> seen, type ==> final ]
  ],
  [ n ==> 3 ]
).

% A global read in a conditional's condition that binds a variable the
% branches read, and one comparing two reads into the same variable.
diag_mod(bind(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> bind_probe,
      arcs ==> [ seen(W, V) : empty => stop(W, V) ] ],
    [ id ==> stop(_, _), type ==> final ]
  ],
  []
).

diag_mod(bind_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty =>
                   (get(goal, D) == a -> seen(yes, D) ; otherwise -> seen(no, wrap(D))) ] ],
    [ id ==> seen(_, _), type ==> final ]
  ],
  []
).

diag_mod(same(Goal),
  [ [ id ==> setup, type ==> neutral,
      arcs ==> [ empty : [set(goal, Goal), set(other, Goal)] => go ] ],
    [ id ==> go, type ==> recursive, embedded_dm ==> same_probe,
      arcs ==> [ seen(W) : empty => stop(W) ] ],
    [ id ==> stop(_), type ==> final ]
  ],
  []
).

diag_mod(same_probe,
  [ [ id ==> begin, type ==> neutral,
      arcs ==> [ empty : empty =>
                   (get(goal, D) == get(other, D) -> seen(D) ; otherwise -> seen(none)) ] ],
    [ id ==> seen(_), type ==> final ]
  ],
  []
).
