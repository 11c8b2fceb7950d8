% list_ops: the operators of the functional language L (semantics.md
% D-30..D-39): get/set/inc on local and global variables, `is`, `=`,
% comparisons, the conditional (C -> A ; otherwise -> B) and the list
% built-ins append, first, rest, push, pop, reverse, member.
%
% `is` collects numbers in the local `items`; `sum` moves them one by one
% into the local `total` through the neutral situation `summing`, whose
% next situation is chosen by a conditional; `done` reports.
diag_mod(main,
  [
    [ id ==> is,
      type ==> speech,
      prog ==> [inc(rounds, _)],
      arcs ==> [
        add(X) : [get(items, L), append(L, [X], L2), set(items, L2)] => is,
        % push/pop work on the front of a list
        undo : [get(items, L), reverse(L, [_|R]), reverse(R, L2),
                set(items, L2), push(undone, [], U), pop(U, P)] => is,
        sum : [get(items, L), member(3, L), P = pair(L, Q), Q = checked]
                => summing,
        done : [get(total, T), get(rounds, R), T > 10, T == 17, R =< 2,
                (get(total, T2) > 10 -> big(T2) ; otherwise -> small(T2))]
                => fs
      ]
    ],
    [ id ==> summing,
      type ==> neutral,
      arcs ==> [
        empty : [get(items, L), first(L, H), rest(L, T), set(items, T),
                 get(total, S), S2 is S + H, set(total, S2)]
                => (T == [] -> is ; otherwise -> summing)
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  [ items ==> [],
    total ==> 0
  ]
).
