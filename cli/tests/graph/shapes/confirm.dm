% confirm(Kind): one answer, yes or no.
diag_mod(confirm(_Kind),
  [
    [ id ==> is,
      type ==> speech,
      arcs ==> [
        y : empty => yes,
        n : empty => no
      ]
    ],
    [ id ==> yes, type ==> final ],
    [ id ==> no, type ==> final ]
  ],
  []
).
