poke/1.
