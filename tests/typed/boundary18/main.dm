% User functions at their boundary (helper `nfun18`, issue 37): a callee
% without locals (`probe`), which the caller (with a local `tag`, also a
% global) pushes on the native stack, calls Prolog user functions in its
% actions, next situations and conditions. Native code calls them where
% the frames are, handing over only where a call fails or a value does
% not convert; each case must give what the interpreter gives
% (tests/tests/suite/typed.rs, `typed::nfun18_*`).
diag_mod(main(Cases),
  [ [ id ==> start, type ==> neutral,
      arcs ==> [ empty : say(apply(reset(_), [x])) => go(Cases) ] ],
    [ id ==> go([]), type ==> final ],
    [ id ==> go([C|Cs]),
      type ==> recursive,
      embedded_dm ==> probe(C),
      arcs ==> [ done(R) : say(R) => go(Cs) ]
    ]
  ],
  [tag ==> caller_local]
).

diag_mod(probe(Case),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => step(Case) ] ],
    % The running DM's variables: `tag` is the caller's local, and a
    % global; the callee has no locals, so the function reads the global.
    [ id ==> step(tag),
      type ==> neutral,
      arcs ==> [ empty : say(apply(tag_of(_), [x])) => done(tag) ]
    ],
    % State between calls (`assert`): two calls, the second's value the
    % next situation's.
    [ id ==> step(count),
      type ==> neutral,
      arcs ==> [ empty : say(apply(counter(_), [x])) => next(apply(counter(_), [y])) ]
    ],
    [ id ==> step(fail), type ==> neutral,
      arcs ==> [ empty : say(apply(fails(_), [x])) => done(fail) ] ],
    [ id ==> step(throw), type ==> neutral,
      arcs ==> [ empty : say(apply(throws(_), [x])) => done(throw) ] ],
    % Values that do not convert: an unbound variable, a compound with one.
    [ id ==> step(unbound), type ==> neutral,
      arcs ==> [ empty : empty => next(apply(unbound(_), [x])) ] ],
    [ id ==> step(shape), type ==> neutral,
      arcs ==> [ empty : empty => next(apply(shape(_), [x])) ] ],
    % The running DM's history (its own level when it is kept).
    [ id ==> step(hist), type ==> neutral,
      arcs ==> [ empty : say(apply(hist(_), [x])) => done(hist) ] ],
    % A condition the machine decides.
    [ id ==> step(cond), type ==> neutral,
      arcs ==> [ empty : empty =>
                   (apply(counter(_), [x]) > 2 -> done(big) ; otherwise -> done(small)) ] ],
    % A global set from a function's value, then read.
    [ id ==> step(global), type ==> neutral,
      arcs ==> [ empty : [assign(V, apply(counter(_), [z])), set(tag, V)] => done(get(tag, _)) ] ],
    % A `get` of a name that is neither a local nor a global.
    [ id ==> step(nowhere), type ==> neutral,
      arcs ==> [ empty : say(apply(nowhere(_), [x])) => done(nowhere) ] ],
    [ id ==> step(_), type ==> neutral, arcs ==> [ empty : empty => done(other) ] ],
    [ id ==> next(N), type ==> neutral, arcs ==> [ empty : say(N) => done(N) ] ],
    [ id ==> done(_), type ==> final ]
  ],
  []
).
