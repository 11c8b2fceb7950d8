% pipe: the in_arg/out_arg pipe (semantics.md D-8, D-9, D-18, D-22).
%
% `is` reads num(V) and pipes V on (the arc's own copy of out_arg);
% `double` binds its out_arg in prog; `sub` runs add_ten on the pipe and,
% having no out_arg, passes on what add_ten returns; `show` expects the
% piped value itself; the final situation wraps the last pipe value.
diag_mod(main,
  [
    [ id ==> is,
      type ==> speech,
      in_arg ==> In,
      out_arg ==> V,
      arcs ==> [
        num(V) : got(In, V) => double,
        stop : bye(In) => fs
      ]
    ],
    [ id ==> double,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> Y,
      prog ==> [Y is X * 2],
      arcs ==> [
        empty : doubled(X, Y) => sub
      ]
    ],
    [ id ==> sub,
      type ==> recursive,
      embedded_dm ==> add_ten,
      arcs ==> [
        done : back => show
      ]
    ],
    % the last arc whose expectation unifies with the input wins
    [ id ==> show,
      type ==> speech,
      in_arg ==> Z,
      arcs ==> [
        Z : matched(Z) => is,
        other : ignored(Z) => is
      ]
    ],
    [ id ==> fs,
      type ==> final,
      in_arg ==> W,
      out_arg ==> result(W)
    ]
  ],
  []
).
