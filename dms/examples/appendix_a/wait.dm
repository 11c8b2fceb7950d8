% Appendix A of the 2021 SitLog paper: the DM `wait` (Listing A4),
% written for sitlog-rs from the paper's listing and description.
%
% One spoken input: the value of the incoming pipe leads to `fs1`, the
% atom `loop` to `fs2`; each way bumps its own global counter.  There is
% no out_arg, so the incoming pipe value flows back to the caller.
diag_mod(wait,
  [
    [ id ==> is,
      type ==> speech,
      in_arg ==> In_Arg,
      arcs ==> [
        In_Arg : [inc(g_count_fs1, _G1)] => fs1,
        loop : [inc(g_count_fs2, _G2)] => fs2
      ]
    ],
    [ id ==> fs1, type ==> final ],
    [ id ==> fs2, type ==> final ]
  ],
  % no local variables
  []
).
