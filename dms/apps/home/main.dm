% The home butler: the conceptual-inference scenario of the 2021 SitLog
% paper (Section 9, turns 1-41, and Appendix B), written for sitlog-rs.
%
% The task is one protocol that embeds its parts: the robot learns the
% words and names it needs from its KB, asks the user's preferences, meets
% the user back from work and takes an order, resolves it by the user's
% preferences, fetches and delivers the items, then reviews what it saw:
% where the delivered items were found (B.3, first part) and objects that
% are not in their place (B.3, abduction). Every sentence comes from the
% world (what the robot sees and hears), the KB and the dialogue state.
diag_mod(main,
  [
    [ id ==> is,
      type ==> recursive,
      embedded_dm ==> learn,
      arcs ==> [ done : empty => preferences ]
    ],
    [ id ==> preferences,
      type ==> recursive,
      embedded_dm ==> preferences,
      arcs ==> [ done : empty => welcome ]
    ],
    [ id ==> welcome,
      type ==> recursive,
      embedded_dm ==> welcome(Order),
      arcs ==> [
        ordered(_) : empty => resolve(Order),
        nothing : empty => closing,
        error(_) : say('I could not meet you.') => closing
      ]
    ],
    [ id ==> resolve(Order),
      type ==> recursive,
      embedded_dm ==> choose(Order, Items),
      arcs ==> [ done(_) : empty => serve(Items) ]
    ],
    [ id ==> serve(Items),
      type ==> recursive,
      embedded_dm ==> serve(Items),
      arcs ==> [ done : empty => review ]
    ],
    [ id ==> review,
      type ==> recursive,
      embedded_dm ==> review,
      arcs ==> [ done : empty => tidy ]
    ],
    [ id ==> tidy,
      type ==> recursive,
      embedded_dm ==> tidy,
      arcs ==> [ done : empty => closing ]
    ],
    [ id ==> closing,
      type ==> neutral,
      arcs ==> [ empty : [say('The task is finished.'), say('Goodbye.')] => fs ]
    ],
    [ id ==> fs,
      type ==> final
    ]
  ],
  []
).
