% The battery level, written with `=>` for `==>`.
battery => 100.
