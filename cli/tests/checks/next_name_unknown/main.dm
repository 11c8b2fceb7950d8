% A new user's next situations (issue 39, session 16): a misspelt name
% with a computed argument, and a `(C -> A ; B)` that is not a
% conditional (its value is the term `;(..)`), name no situation whatever
% their arguments become (E0212).
diag_mod(main,
  [ [id ==> is, type ==> speech,
      arcs ==> [a : empty => serch(get(shelves, _)),
                b : empty => (get(shelves, S), S == [] -> fs ; search(S)),
                c : empty => search(get(shelves, _))]],
    [id ==> search(_), type ==> neutral, arcs ==> [empty : empty => fs]],
    [id ==> fs, type ==> final] ],
  [shelves ==> [fridge]]).
