% Appendix A of the 2021 SitLog paper: the DM `main` (Listing A3),
% written for sitlog-rs from the paper's listing and description.
%
% `is` reads one spoken expectation per visit and counts its visits in
% the local `count_init`; `rs` runs the embedded DM `wait` and counts its
% calls in `count_rec`; `fs` ends the task.
diag_mod(main,
  [
    % initial situation
    [ id ==> is,
      type ==> speech,
      in_arg ==> In_Arg,
      % the outgoing pipe: tuesday when the incoming one is monday,
      % monday otherwise
      out_arg ==> apply(when(_If, _True, _False),
                        [In_Arg == monday, tuesday, monday]),
      prog ==> [inc(count_init, _Count_Init)],
      arcs ==> [
        % a concrete expectation
        finish : screen('Good Bye') => fs,
        % a list holding one open predicate
        [day(X)] : [date(get(day, Y)), next_date(set(day, X))] => is,
        % expectation, action and next situation given by functions
        [get(day, Day), apply(f(X), [In_Arg])] :
            [apply(g(X), [_])] => apply(h(X, Y), [In_Arg, Day])
      ]
    ],
    % recursive situation: runs `wait` on the current pipe value
    [ id ==> rs,
      type ==> recursive,
      prog ==> [inc(count_rec, _Count_Rec)],
      embedded_dm ==> wait,
      arcs ==> [
        fs1 : screen('Back to initial sit') => is,
        fs2 : screen('Cont. recursive sit') => rs
      ]
    ],
    % final situation
    [ id ==> fs,
      type ==> final
    ]
  ],
  % local variables
  [ day ==> monday,
    count_init ==> 0,
    count_rec ==> 0
  ]
).
