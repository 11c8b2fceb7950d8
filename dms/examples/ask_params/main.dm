% ask_params: DM parameters passed by reference (semantics.md D-3, D-20,
% D-23) and recursive situations with several exit arcs (D-22).
%
% main calls ask(Topic, Answer) twice. ask binds its second parameter
% through the diag_mod attribute of the final situation it ends in, so the
% caller's variable holds the answer when the recursive situation's arcs
% run. The arcs are chosen by the id of ask's final situation: got(Value)
% or failed.
diag_mod(main,
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> ask(color, Color),
      arcs ==> [
        got(C) : [set(color, Color), same(C, Color)] => size,
        failed : [no_color(Color)] => size
      ]
    ],
    [ id ==> size,
      type ==> recursive,
      embedded_dm ==> ask(size, Size),
      arcs ==> [
        got(_) : [set(size, Size)] => report,
        failed : [inc(failures, _), no_size(Size)] => report
      ]
    ],
    [ id ==> report,
      type ==> neutral,
      arcs ==> [
        empty : [get(color, C), get(size, S), get(tries, T), order(C, S, T)] => fs
      ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  [ color ==> unknown,
    size ==> unknown
  ]
).
