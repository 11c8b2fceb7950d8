diag_mod(main, [[id ==> fs, type ==> final]], []).
diag_mod(main, [[id ==> fs, type ==> final, colour ==> red]], []).
diag_mod(main(X), [[id ==> fs, type ==> final]], []).
not_a_dm(1).
