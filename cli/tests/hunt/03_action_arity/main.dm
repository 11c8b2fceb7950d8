% Actions with another number of arguments than basic_actions.pl declares.
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [initSpeech, sleep, turn(90, Result), say(hello)] => loud ] ],
    [ id ==> loud, type ==> neutral,
      arcs ==> [ empty : [say(hello, loud)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
