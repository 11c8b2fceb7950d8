% Run-time errors that come from a place in the source (issue 39): each
% case stops the run at an expression, an arc or a situation, and the
% compiled task names the same place (file:line:column) and text as the
% interpreter (tests/tests/suite/typed.rs, `fid21`).
diag_mod(main(Case),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => Case ] ],
    [ id ==> inc_atom, type ==> neutral,
      arcs ==> [ empty : [say(start), inc(name, _)] => fs ] ],
    [ id ==> apply_fails, type ==> neutral,
      arcs ==> [ empty : say(apply(never(_), [x])) => fs ] ],
    [ id ==> is_atom, type ==> neutral, prog ==> [get(name, W), _ is W + 1],
      arcs ==> [ empty : empty => fs ] ],
    [ id ==> by_zero, type ==> neutral,
      arcs ==> [ empty : [say(start), say(apply(ratio(_, _), [1, 0]))] => fs ] ],
    [ id ==> no_situation, type ==> neutral,
      arcs ==> [ empty : say(start) => apply(pair_of(_), [x]) ] ],
    [ id ==> unbound_action, type ==> neutral,
      arcs ==> [ empty : [say(start), A] => next(A) ] ],
    [ id ==> out_fails, type ==> neutral, out_arg ==> apply(never(_), [y]),
      arcs ==> [ empty : say(start) => fs ] ],
    [ id ==> call_fails, type ==> recursive, embedded_dm ==> count(apply(never(_), [z])),
      arcs ==> [ done : empty => fs ] ],
    [ id ==> in_callee, type ==> recursive, embedded_dm ==> count(3),
      arcs ==> [ done : empty => fs ] ],
    [ id ==> overflow, type ==> recursive, embedded_dm ==> big,
      arcs ==> [ done : empty => fs ] ],
    [ id ==> compare_atom, type ==> neutral,
      arcs ==> [ empty : empty => (get(name, _) > 2 -> fs ; otherwise -> fs) ] ],
    [ id ==> next(_), type ==> final ],
    [ id ==> fs, type ==> final ] ],
  [ name ==> bob ]).

% A loop on a typed local: native code; at `n = 3` the divisor is zero.
diag_mod(count(Limit),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(get(n, _)) => (get(n, _) < Limit -> step ; otherwise -> done) ] ],
    [ id ==> step, type ==> neutral, prog ==> [inc(n, _)],
      arcs ==> [ empty : [say(get(n, M)), say(apply(ratio(_, _), [6, 3 - M]))] => is ] ],
    [ id ==> done, type ==> final ] ],
  [ n ==> 0 ]).

% `inc` past the largest integer.
diag_mod(big,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : inc(n, _) => (get(n, _) > 0 -> is ; otherwise -> done) ] ],
    [ id ==> done, type ==> final ] ],
  [ n ==> 9223372036854775806 ]).
