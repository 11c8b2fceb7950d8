% The last hand-overs of the home butler (helper `nbound20`, issue 37),
% in a DM of their shapes; each case must give what the interpreter gives
% (tests/tests/suite/typed.rs, `typed::nbound20_*`):
% - a callee whose only parameter is an output (`fetch(_Got)`, as
%   `welcome(_Order)`), bound by finals whose `diag_mod` is a constant
%   (`fetch([])`) or built (`fetch(Items)`), called natively by a caller
%   whose exit arcs read the output;
% - a ground next situation the evaluator computes (`where(apply(
%   place_here, []))`, as the supermarket's `infer(apply(shop_place_here,
%   []))`), whose value selects `where(unknown)` or `where(P)`, or does
%   not convert (an unbound variable), or fails;
% - a DM no situation calls (`shout(Text, _Status)`, as `say/2`), whose
%   final binds its output by `diag_mod`: run from the command line.
diag_mod(main(Cases),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go(Cases) ] ],
    [ id ==> go([]), type ==> final ],
    [ id ==> go([C|Cs]), type ==> neutral,
      arcs ==> [ empty : set(case, C) => call(Cs) ] ],
    [ id ==> call(Cs),
      type ==> recursive,
      embedded_dm ==> fetch(Got),
      arcs ==> [
        got(_) : empty => show(got(Got), Cs),
        none : empty => show(none(Got), Cs),
        error(E) : empty => show(error(E, Got), Cs)
      ]
    ],
    [ id ==> show(X, Cs), type ==> neutral,
      arcs ==> [ empty : say(X) => go(Cs) ] ]
  ],
  []
).

diag_mod(fetch(_Got),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : empty => step(get(case, _)) ] ],
    [ id ==> step(plain), type ==> neutral,
      arcs ==> [ empty : empty => got([a, b]) ] ],
    [ id ==> step(none), type ==> neutral,
      arcs ==> [ empty : empty => none ] ],
    [ id ==> step(where), type ==> neutral,
      arcs ==> [ empty : empty => where(apply(place_here, [])) ] ],
    [ id ==> step(_), type ==> neutral,
      arcs ==> [ empty : empty => error(unknown_case) ] ],
    [ id ==> where(unknown), type ==> neutral,
      arcs ==> [ empty : empty => none ] ],
    [ id ==> where(P), type ==> neutral,
      arcs ==> [ empty : empty => got([P]) ] ],
    [ id ==> got(Items), type ==> final, diag_mod ==> fetch(Items) ],
    [ id ==> none, type ==> final, diag_mod ==> fetch([]) ],
    [ id ==> error(_), type ==> final, diag_mod ==> fetch([]) ]
  ],
  []
).

diag_mod(shout(Text, _Status),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(Text) => success ] ],
    [ id ==> success, type ==> final, diag_mod ==> shout(Text, ok) ]
  ],
  []
).
