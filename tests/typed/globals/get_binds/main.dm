% `get(v, X)` binds `X` (D-38): a condition's side `get(h, D)` binds `D`
% for the branches after it; an action's `get(g, X)` binds `X` for the
% action's later items and the next situation; `get(v, X)` with `X` bound
% before (by the expectation, by an earlier `get`) unifies: the value
% where they are the same, the machine's error where they differ. For a
% global (`g`, `h`, `k`) and a local (`l`), in caller's exit arcs and in a
% neutral arc. `set(l, ..)` of the local: a constant, a parameter's value.
% The parameters decide which situations are reached and which `get`s
% fail to unify.
diag_mod(main(A, B, C, K),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : [set(g, A), set(h, B), set(l, 0), set(l, C), set(k, K)] => c1 ] ],
    % A condition's `get(h, D)` (a global) binds `D`; its branches read it.
    [ id ==> c1, type ==> recursive, embedded_dm ==> echo(A),
      arcs ==> [ back(V) : empty =>
                   (get(h, D) == V -> (D == x -> c2 ; otherwise -> c2)
                   ; otherwise -> (D == K -> c7 ; otherwise -> c2)) ] ],
    % An action's `get(g, X)` of a fresh `X`: read by the action and the
    % next situation.
    [ id ==> c2, type ==> recursive, embedded_dm ==> echo(B),
      arcs ==> [ back(V) : [get(g, X), X] => (X == V -> c4 ; otherwise -> c3) ] ],
    % `get(g, V)` with `V` bound by the expectation: `g` is `A`, `V` is `B`.
    [ id ==> c3, type ==> recursive, embedded_dm ==> echo(B),
      arcs ==> [ back(V) : [get(g, V), V] => c4 ] ],
    % The local: `get(l, X)` fresh, then bound by the first, in an action;
    % a condition's `get(l, E)` read in its branch.
    [ id ==> c4, type ==> recursive, embedded_dm ==> echo(B),
      arcs ==> [ back(V) : [get(l, X), X, get(l, X)] =>
                   (get(l, E) == V -> c5 ; otherwise -> (E == X -> c6 ; otherwise -> c5)) ] ],
    % `get(l, V)` with `V` bound by the expectation: `l` is `C`, `V` is `K`.
    [ id ==> c5, type ==> recursive, embedded_dm ==> echo(K),
      arcs ==> [ back(V) : [get(l, V)] => c6 ] ],
    % A neutral arc: `get(l, X)` then `X`, a condition on a global read into
    % `G` and read again; an arithmetic one on `k`.
    [ id ==> c6, type ==> neutral,
      arcs ==> [ empty : [get(l, X), X] =>
                   (get(g, G) == X -> c7 ; otherwise -> (G == A -> c7 ; otherwise -> c7)) ] ],
    % `get(k, N)` inside a comparison, `N` read again.
    [ id ==> c7, type ==> recursive, embedded_dm ==> echo(K),
      arcs ==> [ back(V) : empty =>
                   (get(k, N) > 1 -> (N == V -> c8 ; otherwise -> c8) ; otherwise -> (N < 0 -> c8 ; otherwise -> c8)) ] ],
    % Two sides into the same `D`: the second unifies (`g` is `A`, `h` is `B`).
    [ id ==> c8, type ==> recursive, embedded_dm ==> echo(K),
      arcs ==> [ back(_) : empty => (get(g, D) == get(h, D) -> over ; otherwise -> over) ] ],
    [ id ==> over, type ==> final ]
  ],
  [ l ==> 0 ]
).

diag_mod(echo(X),
  [ [ id ==> e, type ==> neutral, arcs ==> [ empty : empty => back(X) ] ],
    [ id ==> back(X), type ==> final ]
  ],
  []
).
