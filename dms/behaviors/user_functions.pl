% The behaviour library checked on its own (`sitlogc check dms/behaviors`):
% its DMs call the language functions of language.pl. Applications that
% use the library consult language.pl from their own user_functions.pl.

:- consult('language.pl').
