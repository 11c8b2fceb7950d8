% typed_calls: DM calls that compiled code makes on typed frames
% (`sitlogc build --explain-types` shows them), and every way such a call
% hands over to the machine, which must not change what the task does:
%
% - `measure` calls `bump`, which has two final situations: the exit arc
%   is chosen by the callee's final id;
% - `dive` calls `down`, which calls itself until the pipe reaches 0: the
%   first 36 levels are deeper than the compiled code's typed DM stack, so
%   the deeper calls go through the machine's DM stack;
% - `count` calls `upto(3)`, a constant call with an argument: the callee's
%   frame holds its parameter as an integer; `bad` calls `upto(many)`,
%   whose frame does not load: the callee runs on terms (and fails to
%   compare `many`, an error on both back ends); `over` calls `wrap`,
%   whose `inc` overflows: the error names `wrap`, where it happened;
% - `spoil` leaves a float in the pipe: the typed frames, which hold the
%   pipe as an integer, no longer load, and everything after runs on terms.
diag_mod(main,
  [
    [ id ==> init,
      type ==> neutral,
      out_arg ==> P,
      prog ==> [P is 35],
      arcs ==> [ empty : empty => start ]
    ],
    [ id ==> start,
      type ==> speech,
      arcs ==> [
        go : [inc(rounds, _)] => measure,
        dive : empty => dive,
        count : empty => counting,
        bad : empty => counting_bad,
        over : empty => overflowing,
        spoil : empty => spoiling,
        stop : say(bye) => fs
      ]
    ],
    [ id ==> measure,
      type ==> recursive,
      embedded_dm ==> bump,
      arcs ==> [
        high : say(high) => gate,
        low : say(low) => gate
      ]
    ],
    [ id ==> dive,
      type ==> recursive,
      embedded_dm ==> down,
      arcs ==> [ bottom : say(bottom) => gate ]
    ],
    [ id ==> counting,
      type ==> recursive,
      embedded_dm ==> upto(3),
      arcs ==> [ done : say(counted) => gate ]
    ],
    [ id ==> counting_bad,
      type ==> recursive,
      embedded_dm ==> upto(many),
      arcs ==> [ done : say(counted) => gate ]
    ],
    [ id ==> overflowing,
      type ==> recursive,
      embedded_dm ==> wrap,
      arcs ==> [ done : empty => gate ]
    ],
    [ id ==> spoiling,
      type ==> recursive,
      embedded_dm ==> spoil,
      arcs ==> [ spoiled : say(spoiled) => gate ]
    ],
    % the pipe, read back after the calls
    [ id ==> gate,
      type ==> neutral,
      in_arg ==> X,
      arcs ==> [ empty : empty => (X >= 1000 -> fs ; otherwise -> start) ]
    ],
    [ id ==> fs, type ==> final ]
  ],
  [ rounds ==> 0 ]
).

% Adds 1 to the pipe; ends in `high` from 30 on, else in `low`.
diag_mod(bump,
  [
    [ id ==> add,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> Y,
      prog ==> [Y is X + 1],
      arcs ==> [ empty : empty => (Y >= 30 -> high ; otherwise -> low) ]
    ],
    [ id ==> high, type ==> final ],
    [ id ==> low, type ==> final ]
  ],
  []
).

% Takes 1 from the pipe and calls itself until it is 0 or less.
diag_mod(down,
  [
    [ id ==> dec,
      type ==> neutral,
      in_arg ==> X,
      out_arg ==> Y,
      prog ==> [Y is X - 1],
      arcs ==> [ empty : [inc(steps, _)] => (Y > 0 -> again ; otherwise -> bottom) ]
    ],
    [ id ==> again,
      type ==> recursive,
      embedded_dm ==> down,
      arcs ==> [ bottom : empty => bottom ]
    ],
    [ id ==> bottom, type ==> final ]
  ],
  [ steps ==> 0 ]
).

% Leaves 2.5 in the pipe (its out_arg is a constant: untyped code).
diag_mod(spoil,
  [
    [ id ==> put,
      type ==> neutral,
      out_arg ==> 2.5,
      arcs ==> [ empty : empty => spoiled ]
    ],
    [ id ==> spoiled, type ==> final ]
  ],
  []
).

% Counts its local up to its parameter.
diag_mod(upto(Max),
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(c, C)] => (C >= Max -> done ; otherwise -> is) ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ c ==> 0 ]
).

% Its counter starts at the largest integer: `inc` overflows.
diag_mod(wrap,
  [
    [ id ==> is,
      type ==> neutral,
      arcs ==> [ empty : [inc(c, _)] => done ]
    ],
    [ id ==> done, type ==> final ]
  ],
  [ c ==> 9223372036854775807 ]
).
