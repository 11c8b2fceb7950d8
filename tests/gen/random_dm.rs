//! A deterministic generator of random, well-formed SitLog applications for
//! the compiled-vs-interpreted agreement test (issue 5).
//!
//! One copy, two users: `tests/build.rs` includes it with
//! `#[path = "gen/random_dm.rs"]` to write and compile the programs of [`seeds`]
//! at build time, and `tests/src/lib.rs` includes it as
//! `sitlog_tests::random_dm` for the test that runs them interpreted.
//! No external crates: a splitmix64 generator seeded by an integer. One file
//! of over 800 lines because the build script includes it by `#[path]`: a
//! module directory could not be included there.
//!
//! What a program holds: 1–3 DMs (`main`, `sub1`, `sub2`; subs take 0–2
//! parameters, the last one a result bound by a final's `diag_mod`), each
//! with several situations: `speech` ones whose arcs expect atoms, `said(X)`,
//! `num(N)`, lists, the in_arg value, `get`/`inc` of a local or a bare
//! variable; `neutral` ones `[empty : A => N]`; `recursive` ones calling
//! other DMs (by parameters, with one exit arc per final situation);
//! countdowns `tick(0)`/`tick(N)` (two situations sharing a functor, D-21)
//! and list walks `tick([])`/`tick([H|T])` (an id that is a pattern, whose
//! head may also be the in_arg);
//! speech situations with a parameter `ask(K)` reached by `ask(2)`; final
//! situations with `out_arg` and `diag_mod`. Actions use local variables
//! (`n`, `m`, `l`, `v`) and global ones (`g_count`, `g_log` in
//! `global_vars.pl`) through `get`/`set`/`inc`, `is`, `=`, `append`,
//! `member` and conditionals `(C -> A ; otherwise -> B)`; next situations
//! may be conditionals too. The pipe flows through `in_arg`/`out_arg`
//! (including an out_arg bound by `prog`).
//!
//! Runs are finite for every script: only situations that read input
//! (speech situations and recursive situations whose callee starts with a
//! speech situation) may jump backwards or call a DM that is not below
//! them; every other jump goes forwards in situation order, counts down a
//! `tick(N)`, or is a back edge guarded by the local counter `n`
//! (`inc(n, C)` then `(C >= K -> forwards ; otherwise -> back)`), which
//! only speech arcs reset. So every cycle of the run reads input, and
//! scripts are finite.
//!
//! A few constructs are errors at run time on purpose (rarely, and never
//! in main's first situation): an `in_arg` pattern `w(In)` that the pipe
//! seldom matches, a recursive situation without an exit arc for one of its
//! callee's finals, a `diag_mod` that does not unify with the DM's id, an
//! `inc` of a non-number, a next situation named by the input
//! (`said(X) : ... => X`). Both back ends must report the same error.
//!
//! Besides these, walker programs (seeds from [`WALKER_SEED`], `walkers`:
//! one list walked by a compound id) and two-list walker programs (seeds
//! from [`PAIR_SEED`], `pair_walkers`: two lists in step, finals carrying
//! compounds the caller destructures) read no input.
//!
//! Only the first arc of a speech situation may expect a bare variable (it
//! meets every input, and the last matching arc wins), so the other arcs
//! still get their turn.

/// The seeds of the random programs `tests/build.rs` generates, from the
/// generator's seeds `0..24`: 12 of them that together make every construct
/// the generator has (the rare ones: an `in_arg` pattern `w(In)` in seed 12
/// only, a `diag_mod` that does not unify with the caller's argument in 17
/// and 20), which `random_agreement.rs` checks. Each program is about
/// 175 KB of generated Rust; all 24 were 8 s more CPU to compile than these
/// 12 (docs/guide/testing.md). When the generator changes, that check says
/// which construct the seeds no longer make: pick seeds that make it.
pub const SEEDS: &[u64] = &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 20];

/// The first seed of the walker programs (issue 37, `walkers`):
/// seeds `WALKER_SEED..WALKER_SEED + WALKERS`.
pub const WALKER_SEED: u64 = 1000;
/// How many walker programs `tests/build.rs` generates.
pub const WALKERS: u64 = 6;

/// The first seed of the two-list walker programs (helper `review19`,
/// issue 37, `pair_walkers`): seeds `PAIR_SEED..PAIR_SEED + pairs()`.
pub const PAIR_SEED: u64 = 2000;

/// How many two-list walker programs `tests/build.rs` generates: 3, or
/// `SITLOG_RANDOM_PAIRS` at build time (a knob for many seeds: each is a
/// program compiled into the test library, about 45 KB of generated Rust).
pub fn pairs() -> u64 {
    option_env!("SITLOG_RANDOM_PAIRS").map_or(3, |n| n.parse().expect("SITLOG_RANDOM_PAIRS"))
}

/// The first seed of the recursive walker programs (helper `tidy23`,
/// issue 37, `rec_walkers`): seeds `REC_SEED..REC_SEED + REC_WALKERS`.
pub const REC_SEED: u64 = 3000;
/// How many recursive walker programs `tests/build.rs` generates.
pub const REC_WALKERS: u64 = 3;

/// Every seed `tests/build.rs` generates a program for, in order.
pub fn seeds() -> impl Iterator<Item = u64> {
    SEEDS
        .iter()
        .copied()
        .chain(WALKER_SEED..WALKER_SEED + WALKERS)
        .chain(PAIR_SEED..PAIR_SEED + pairs())
        .chain(REC_SEED..REC_SEED + REC_WALKERS)
}

/// The input terms scripts are drawn from: the atoms and terms the arcs
/// expect plus terms that match nothing (`zz`, `said(zz)`, `huh(1)`).
pub const VOCABULARY: &[&str] = &[
    "a",
    "b",
    "c",
    "yes",
    "no",
    "stop",
    "said(a)",
    "said(b)",
    "said(hello)",
    "num(0)",
    "num(1)",
    "num(2)",
    "num(3)",
    "[a,b]",
    "[a,c]",
    "[c,b]",
    "1",
    "2",
    "none",
    "p(none)",
    "zz",
    "said(zz)",
    "huh(1)",
];

/// Terms that match nothing any program expects.
pub const NOISE: &[&str] = &["zz", "said(zz)", "huh(1)"];

/// The input terms a script for program `seed` may be drawn from: one that
/// matches each expectation the program has (where one can be told in
/// advance), then [`NOISE`]. A subset of [`VOCABULARY`].
pub fn inputs(seed: u64) -> Vec<String> {
    generate(seed).1
}

/// A test-mode script: one term per line, each ending with `.`.
pub fn script(terms: &[&str]) -> String {
    let mut s = String::new();
    for t in terms {
        s.push_str(t);
        s.push_str(".\n");
    }
    s
}

/// The application of `seed`: (file name, content) pairs for one directory
/// (`models`, `global_vars.pl`, one `.dm` file per DM). Its main DM is
/// `main`, run with the default in_arg.
pub fn program(seed: u64) -> Vec<(String, String)> {
    generate(seed).0
}

/// The files of program `seed` and its [`inputs`].
fn generate(seed: u64) -> (Vec<(String, String)>, Vec<String>) {
    if seed >= REC_SEED {
        return rec_walkers(seed);
    }
    if seed >= PAIR_SEED {
        return pair_walkers(seed);
    }
    if seed >= WALKER_SEED {
        return walkers(seed);
    }
    let mut rng = Rng::new(seed);
    let plans = plan(&mut rng);
    let mut files = Vec::new();
    let mut inputs: Vec<&'static str> = Vec::new();
    let mut models = format!("% random program {seed}, generated by tests/gen/random_dm.rs\n");
    for (i, p) in plans.iter().enumerate() {
        let mut gen = Gen::new(&plans, i, &mut rng);
        let text = gen.dm();
        for t in gen.inputs {
            if !inputs.contains(&t) {
                inputs.push(t);
            }
        }
        let file = format!("{}.dm", p.name);
        models.push_str(&format!("'{file}'.\n"));
        files.push((file, text));
    }
    inputs.extend_from_slice(NOISE);
    files.push(("models".to_owned(), models));
    files.push((
        "global_vars.pl".to_owned(),
        "g_count ==> 0.\ng_log ==> [].\n".to_owned(),
    ));
    (files, inputs.into_iter().map(str::to_owned).collect())
}

// --------------------------------------------------------------- walkers

/// The elements the walkers' lists are made of, by kind: atoms, ints,
/// lists.
const WALK_ELEMENTS: [&[&str]; 3] = [
    &["a", "b", "c", "d"],
    &["0", "1", "2", "7", "9"],
    &["[]", "[a]", "[b, c]", "[a, a]"],
];

/// A walker call's list (0–5 elements, written without brackets) and
/// target: of the walker's element kind `own`, or one-fifth of the time of
/// any kind.
fn list_and_target(rng: &mut Rng, own: usize) -> (String, &'static str) {
    let kind = if rng.chance(20) { rng.below(3) } else { own };
    let len = rng.range(0, 6);
    let items: Vec<&str> = (0..len).map(|_| *rng.pick(WALK_ELEMENTS[kind])).collect();
    (items.join(", "), *rng.pick(WALK_ELEMENTS[kind]))
}

/// A walker program's files (its DMs in `main.dm`) and inputs (it reads
/// none: one atom, never read).
fn one_file(text: String) -> (Vec<(String, String)>, Vec<String>) {
    let files = vec![
        ("main.dm".to_owned(), text),
        ("models".to_owned(), "'main.dm'.\n".to_owned()),
        (
            "global_vars.pl".to_owned(),
            "g_count ==> 0.\ng_log ==> [].\n".to_owned(),
        ),
    ];
    (files, vec!["a".to_owned()])
}

/// A walker program (issue 37): shapes the generated code runs natively.
/// `main` calls 2–4 walker DMs `wI(List, Target)` in turn with constant
/// arguments (lists of atoms, of ints or of lists, possibly empty; a
/// walker called with lists of two kinds gets `term` parameters, held as
/// ground terms), one exit arc per final situation. A walker goes through
/// its list by the compound id `st(..)`: `st([])`; in random order some of
/// `st([c|_])` (a constant head), `st([X, X|_])` (a repeated variable); then
/// `st([X|R])` comparing `X` with the target (`==`, `\==`, or `>` on ints),
/// maybe saying `X` (an effector's action), ending in `hit(X)`, `dup(X)`,
/// `fixed(c)` or `none`; `st([])` maybe on terms (a `get`: the walk crosses
/// from native code to term code and back). Some calls go through a relay
/// `rI(List, Target)` that calls `wI` and hands its final on (nested native
/// calls, a local counted by `inc` in an exit arc); `main` counts hits in a
/// local too. No input is read.
fn walkers(seed: u64) -> (Vec<(String, String)>, Vec<String>) {
    let mut rng = Rng::new(seed);
    let lists = WALK_ELEMENTS;
    let n = rng.range(1, 3);
    let mut text = format!("% walker program {seed}, generated by tests/gen/random_dm.rs\n");
    // Element kind of each walker: its first call's; later calls may mix.
    let kinds: Vec<usize> = (0..n).map(|_| rng.below(3)).collect();
    let mut main_sits = Vec::new();
    let mut relayed = vec![false; n];
    let calls = rng.range(2, 4);
    for j in 0..calls {
        let w = rng.below(n);
        let callee = if rng.chance(40) {
            relayed[w] = true;
            format!("r{w}")
        } else {
            format!("w{w}")
        };
        let (items, target) = list_and_target(&mut rng, kinds[w]);
        let next = if j + 1 == calls {
            "fs".to_owned()
        } else {
            format!("s{}", j + 1)
        };
        main_sits.push(format!(
            "    [ id ==> s{j}, type ==> recursive, embedded_dm ==> {callee}([{items}], {target}),\n      \
             arcs ==> [ hit(_) : [inc(k, _)] => {next}, dup(_) : empty => {next}, \
             fixed(_) : empty => {next}, none : empty => {next} ] ],\n"
        ));
    }
    text.push_str("diag_mod(main,\n  [\n");
    for s in &main_sits {
        text.push_str(s);
    }
    text.push_str("    [ id ==> fs, type ==> final ]\n  ],\n  [ k ==> 0 ]\n).\n");
    for (w, _) in relayed.iter().enumerate().filter(|(_, r)| **r) {
        text.push_str(&format!(
            "\ndiag_mod(r{w}(L, T),\n  [ [ id ==> go, type ==> recursive, embedded_dm ==> w{w}(L, T),\n      \
             arcs ==> [ hit(X) : [inc(c, _)] => hit(X), dup(X) : empty => dup(X), \
             fixed(X) : empty => fixed(X), none : empty => none ] ],\n    \
             [ id ==> hit(X), type ==> final ], [ id ==> dup(X), type ==> final ],\n    \
             [ id ==> fixed(X), type ==> final ], [ id ==> none, type ==> final ]\n  ],\n  \
             [ c ==> 0 ]\n).\n"
        ));
    }
    for (w, &kind) in kinds.iter().enumerate() {
        // Native code per situation (issue 37): `st([])` sometimes stays
        // on terms (a `get`), so the walk crosses to the term code and back.
        let nil_action = if rng.chance(40) {
            "get(g_count, _)"
        } else {
            "empty"
        };
        let mut sits = vec![
            "    [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => st(L) ] ],\n"
                .to_owned(),
            format!(
                "    [ id ==> st([]), type ==> neutral, arcs ==> [ empty : {nil_action} => none ] ],\n"
            ),
        ];
        let mut extra = Vec::new();
        if rng.chance(50) {
            let c = *rng.pick(lists[kind]);
            extra.push(format!(
                "    [ id ==> st([{c}|_]), type ==> neutral, arcs ==> [ empty : empty => fixed({c}) ] ],\n"
            ));
        }
        if rng.chance(50) {
            extra.push(
                "    [ id ==> st([X, X|_]), type ==> neutral, arcs ==> [ empty : empty => dup(X) ] ],\n"
                    .to_owned(),
            );
        }
        if rng.chance(50) {
            extra.reverse();
        }
        sits.extend(extra);
        let cmp = match (kind, rng.below(3)) {
            (1, 0) => "X > T",
            (_, 1) => "X \\== T",
            _ => "X == T",
        };
        // An effector's action built from native values.
        let action = if rng.chance(50) {
            "say(['at', X, of, T])"
        } else {
            "empty"
        };
        sits.push(format!(
            "    [ id ==> st([X|R]), type ==> neutral,\n      \
             arcs ==> [ empty : {action} => ({cmp} -> hit(X) ; otherwise -> st(R)) ] ],\n"
        ));
        for f in ["hit(X)", "dup(X)", "fixed(X)", "none"] {
            sits.push(format!("    [ id ==> {f}, type ==> final ],\n"));
        }
        let last = sits.len() - 1;
        sits[last] = sits[last].replace("],\n", "]\n");
        text.push_str(&format!("\ndiag_mod(w{w}(L, T),\n  [\n"));
        for s in &sits {
            text.push_str(s);
        }
        text.push_str("  ],\n  []\n).\n");
    }
    one_file(text)
}

/// A two-list walker program (helper `review19`, issue 37): `main` calls
/// 2–4 walkers `zI(Xs, Ys, T)` (directly, or through a relay `qI` that
/// hands the final on) with constant lists of atoms or ints of 0–5
/// elements each, not always of one length (the first call's are). A walker goes through both
/// lists in step by the compound id `st(Xs, Ys)` (or `st(Xs, Ys, C)`
/// counting the steps by `is`): `st([], [])` ends in `both`; `st([X|Xs],
/// [Y|Ys])` compares `X` or `Y` with the target, or `X` with `Y`, ending in
/// a final that carries a compound, `got(X, Y)`, `at(pos(X), C)` or
/// `same(X)`; a fallback `st(A, B)` for lists of different lengths ends in
/// `uneven(A)`, or is missing (no situation matches: an error both back
/// ends must report alike). The caller's exit arcs destructure the finals
/// (`got(a, Y)` before `got(X, Y)`, `at(pos(P), N)` with `N` stored in a
/// local); one of them may be missing after the first call (a final no
/// exit arc matches: an error). A final may hand `[X, Y]` down the pipe by its out_arg, which
/// `main`'s final receives. No input is read.
fn pair_walkers(seed: u64) -> (Vec<(String, String)>, Vec<String>) {
    let mut rng = Rng::new(seed);
    let lists: [&[&str]; 2] = [&["a", "b", "c"], &["0", "1", "2", "7"]];
    let n = rng.range(1, 2);
    let mut text =
        format!("% two-list walker program {seed}, generated by tests/gen/random_dm.rs\n");
    let counted: Vec<bool> = (0..n).map(|_| rng.chance(40)).collect();
    let fallback: Vec<bool> = (0..n).map(|_| rng.chance(75)).collect();
    let outs: Vec<bool> = (0..n).map(|_| rng.chance(40)).collect();
    let finals = |w: usize| -> Vec<String> {
        let mut f = vec![
            "got(X, Y)".to_owned(),
            "same(X)".to_owned(),
            "both".to_owned(),
        ];
        if counted[w] {
            f.push("at(pos(X), C)".to_owned());
        }
        if fallback[w] {
            f.push("uneven(A)".to_owned());
        }
        f
    };
    let mut relayed = vec![false; n];
    let calls = rng.range(2, 4);
    let mut main_sits = Vec::new();
    for j in 0..calls {
        let w = rng.below(n);
        let callee = if rng.chance(30) {
            relayed[w] = true;
            format!("q{w}")
        } else {
            format!("z{w}")
        };
        let kind = rng.below(2);
        // The first call's lists of one length, so every program makes a
        // few transitions before an error.
        let (lx, ly) = if j == 0 || rng.chance(70) {
            let l = rng.range(0, 5);
            (l, l)
        } else {
            (rng.range(0, 5), rng.range(0, 5))
        };
        let xs: Vec<&str> = (0..lx).map(|_| *rng.pick(lists[kind])).collect();
        let ys: Vec<&str> = (0..ly).map(|_| *rng.pick(lists[kind])).collect();
        let target = *rng.pick(lists[kind]);
        let next = if j + 1 == calls {
            "fs".to_owned()
        } else {
            format!("s{}", j + 1)
        };
        let c0 = lists[kind][0];
        let mut arcs = vec![
            format!("got({c0}, Y) : [set(v, Y)] => {next}"),
            format!("got(X, Y) : [set(v, X)] => {next}"),
            format!("same(X) : [inc(k, _)] => {next}"),
            format!("both : empty => {next}"),
        ];
        if counted[w] {
            arcs.push(format!("at(pos(P), N) : [set(v, P), set(k, N)] => {next}"));
        }
        if fallback[w] {
            arcs.push(format!("uneven(R) : [set(v, R)] => {next}"));
        }
        // Rarely, no exit arc for one of the callee's finals (an error).
        if j > 0 && rng.chance(10) {
            let k = rng.range(1, arcs.len() - 1);
            arcs.remove(k);
        }
        main_sits.push(format!(
            "    [ id ==> s{j}, type ==> recursive, embedded_dm ==> {callee}([{}], [{}], {target}),\n      \
             arcs ==> [ {} ] ],\n",
            xs.join(", "),
            ys.join(", "),
            arcs.join(",\n                 ")
        ));
    }
    let mut main = "diag_mod(main,\n  [\n".to_owned();
    for s in &main_sits {
        main.push_str(s);
    }
    main.push_str(
        "    [ id ==> fs, type ==> final, in_arg ==> _In ]\n  ],\n  [ k ==> 0, v ==> none ]\n).\n",
    );
    text.push_str(&mark_singletons(&main));
    for (w, _) in relayed.iter().enumerate().filter(|(_, r)| **r) {
        let fs = finals(w);
        let arcs: Vec<String> = fs.iter().map(|f| format!("{f} : empty => {f}")).collect();
        let sits: Vec<String> = fs
            .iter()
            .map(|f| format!("    [ id ==> {f}, type ==> final ]"))
            .collect();
        text.push_str(&mark_singletons(&format!(
            "\ndiag_mod(q{w}(Xs, Ys, T),\n  [ [ id ==> go, type ==> recursive, embedded_dm ==> z{w}(Xs, Ys, T),\n      \
             arcs ==> [ {} ] ],\n{}\n  ],\n  []\n).\n",
            arcs.join(",\n                 "),
            sits.join(",\n")
        )));
    }
    for w in 0..n {
        let (st, st_nil, st_cons, step) = if counted[w] {
            (
                "st(Xs, Ys, 0)",
                "st([], [], _)",
                "st([X|Xs1], [Y|Ys1], C)",
                "st(Xs1, Ys1, C1 is C + 1)",
            )
        } else {
            (
                "st(Xs, Ys)",
                "st([], [])",
                "st([X|Xs1], [Y|Ys1])",
                "st(Xs1, Ys1)",
            )
        };
        let hit = match (counted[w], rng.below(3)) {
            (true, 0) => "at(pos(X), C)",
            (_, 1) => "same(X)",
            _ => "got(X, Y)",
        };
        let cmp = match rng.below(4) {
            0 => "X == T",
            1 => "Y == T",
            2 => "X == Y",
            _ => "X \\== T",
        };
        let mut sits = vec![
            format!("    [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => {st} ] ]"),
            format!(
                "    [ id ==> {st_nil}, type ==> neutral, arcs ==> [ empty : empty => both ] ]"
            ),
            format!(
                "    [ id ==> {st_cons}, type ==> neutral,\n      \
                 arcs ==> [ empty : empty => ({cmp} -> {hit} ; otherwise -> {step}) ] ]"
            ),
        ];
        if fallback[w] {
            let fb = if counted[w] {
                "st(A, _, _)"
            } else {
                "st(A, _)"
            };
            sits.push(format!(
                "    [ id ==> {fb}, type ==> neutral, arcs ==> [ empty : empty => uneven(A) ] ]"
            ));
        }
        for f in finals(w) {
            let out = if outs[w] && f == "got(X, Y)" {
                ", out_arg ==> [X, Y]"
            } else {
                ""
            };
            sits.push(format!("    [ id ==> {f}, type ==> final{out} ]"));
        }
        text.push_str(&mark_singletons(&format!(
            "\ndiag_mod(z{w}(Xs, Ys, T),\n  [\n{}\n  ],\n  []\n).\n",
            sits.join(",\n")
        )));
    }
    one_file(text)
}

// ------------------------------------------------------- recursive walkers

/// A recursive walker program (helper `tidy23`, issue 37's "the random-DM
/// agreement test generates atoms, lists and compound ids"): `main` puts
/// an int in the pipe, then calls 2–3 walkers `vI(List, Target)` with
/// constant arguments (lists of atoms, ints or lists; the target of the
/// same kind, or not), counting finds in a local. A walker goes through
/// its list by the recursive compound id `try([P|Ps], I)` (a list and an
/// int), calling `cI(P, Target, tag)` on each element (a call with
/// arguments, one an atom), whose final `same(X)` or `other` the exit arcs
/// take: `found(P, I)` (a compound final with the element and the index;
/// maybe `out_arg ==> I` into the pipe), or the next `try(Ps, _J is I + 1)`,
/// maybe stopped by a limit read from the pipe (`in_arg ==> Lim` on the
/// recursive situation, `I >= Lim`) or said (`say([at, P])`). The callee
/// passes the pipe on (`in_arg ==> N, out_arg ==> N`) or not. No input is
/// read.
fn rec_walkers(seed: u64) -> (Vec<(String, String)>, Vec<String>) {
    let mut rng = Rng::new(seed);
    let n = rng.range(1, 2);
    let mut text =
        format!("% recursive walker program {seed}, generated by tests/gen/random_dm.rs\n");
    // The first walker's element kind, limit and `say` follow the seed, so
    // that the `REC_WALKERS` programs together have each.
    let idx = seed.wrapping_sub(REC_SEED) as usize;
    let kinds: Vec<usize> = (0..n)
        .map(|w| if w == 0 { idx % 3 } else { rng.below(3) })
        .collect();
    let calls = rng.range(2, 3);
    let limit = rng.range(0, 4);
    text.push_str(&format!(
        "diag_mod(main,\n  [\n    [ id ==> s0, type ==> neutral, out_arg ==> {limit}, \
         arcs ==> [ empty : empty => s1 ] ],\n"
    ));
    for j in 1..=calls {
        let w = rng.below(n);
        let (items, target) = list_and_target(&mut rng, kinds[w]);
        let next = if j == calls {
            "fs".to_owned()
        } else {
            format!("s{}", j + 1)
        };
        text.push_str(&format!(
            "    [ id ==> s{j}, type ==> recursive, embedded_dm ==> v{w}([{items}], {target}),\n      \
             arcs ==> [ found(_, _) : [inc(k, _)] => {next}, not_found(_) : empty => {next} ] ],\n"
        ));
    }
    text.push_str("    [ id ==> fs, type ==> final ]\n  ],\n  [ k ==> 0 ]\n).\n");
    for w in 0..n {
        let limited = if w == 0 { idx % 3 != 1 } else { rng.chance(50) };
        let (in_arg, test) = if limited {
            ("in_arg ==> Lim, ", "I >= Lim")
        } else {
            ("", "I >= 99")
        };
        let action = if (w == 0 && !idx.is_multiple_of(3)) || rng.chance(40) {
            "say([at, P])"
        } else {
            "empty"
        };
        let (found, out) = if rng.chance(50) {
            ("found(_P, I)", ", out_arg ==> I")
        } else {
            ("found(_P, _I)", "")
        };
        let (same, other) = if rng.chance(50) {
            ("X == Y", "same(X) ; otherwise -> other")
        } else {
            ("X \\== Y", "other ; otherwise -> same(X)")
        };
        let pipe = if rng.chance(50) {
            "in_arg ==> N, out_arg ==> N, "
        } else {
            ""
        };
        text.push_str(&format!(
            "\ndiag_mod(v{w}(Ps, T),\n  [\n    \
             [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => try(Ps, 0) ] ],\n    \
             [ id ==> try([], I), type ==> neutral, arcs ==> [ empty : empty => not_found(I) ] ],\n    \
             [ id ==> try([P|Rest], I), type ==> recursive, {in_arg}embedded_dm ==> c{w}(P, T, tag),\n      \
             arcs ==> [ same(Q) : {action} => found(Q, I),\n                 \
             other : {action} => ({test} -> not_found(I) ; otherwise -> try(Rest, _J is I + 1)) ] ],\n    \
             [ id ==> {found}, type ==> final{out} ],\n    \
             [ id ==> not_found(_I), type ==> final ]\n  ],\n  []\n).\n"
        ));
        text.push_str(&format!(
            "\ndiag_mod(c{w}(X, Y, _Tag),\n  [\n    \
             [ id ==> is, type ==> neutral, {pipe}arcs ==> [ empty : empty => ({same} -> {other}) ] ],\n    \
             [ id ==> same(_X), type ==> final ],\n    \
             [ id ==> other, type ==> final ]\n  ],\n  []\n).\n"
        ));
    }
    one_file(text)
}

// ------------------------------------------------------------------ PRNG

/// splitmix64.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        let mut r = Rng(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0x9E37_79B9_7F4A_7C15);
        r.next();
        r
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// Uniform in `lo..=hi`.
    fn range(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.below(hi - lo + 1)
    }

    /// True with probability `percent`/100.
    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

// ------------------------------------------------------------------ plan

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Speech,
    Neutral,
    /// Calls the DM of that index.
    Recursive(usize),
    /// `tickJ(0)` then `tickJ(N)`: a countdown of neutral situations.
    Tick,
    /// `askJ(K)`: a speech situation with a (numeric) parameter.
    Ask,
}

struct Plan {
    name: String,
    /// 0: `sub`; 1: `sub(Result)`; 2: `sub(Param, Result)`.
    arity: usize,
    /// The first situation reads input (so every call of the DM does).
    reading: bool,
    kinds: Vec<Kind>,
    /// Per final situation: does its id take a parameter (`gotK(A)`)?
    finals: Vec<bool>,
    has_m: bool,
    has_l: bool,
    has_v: bool,
}

impl Plan {
    fn final_id(&self, k: usize) -> String {
        if self.finals[k] {
            format!("got{k}")
        } else {
            format!("f{k}")
        }
    }
}

fn plan(rng: &mut Rng) -> Vec<Plan> {
    let n = match rng.below(10) {
        0..=1 => 1,
        2..=5 => 2,
        _ => 3,
    };
    let mut plans: Vec<Plan> = (0..n)
        .map(|i| {
            let main = i == 0;
            Plan {
                name: if main {
                    "main".to_owned()
                } else {
                    format!("sub{i}")
                },
                arity: if main { 0 } else { rng.below(3) },
                reading: rng.chance(if main { 80 } else { 55 }),
                kinds: Vec::new(),
                finals: (0..rng.range(1, if main { 2 } else { 3 }))
                    .map(|_| rng.chance(40))
                    .collect(),
                has_m: rng.chance(70),
                has_l: rng.chance(40),
                has_v: rng.chance(50),
            }
        })
        .collect();
    let reading: Vec<bool> = plans.iter().map(|p| p.reading).collect();
    for (i, p) in plans.iter_mut().enumerate() {
        let callees: Vec<usize> = (0..n).filter(|&j| j > i || reading[j]).collect();
        let count = if i == 0 {
            rng.range(4, 7)
        } else {
            rng.range(2, 5)
        };
        for j in 0..count {
            let kind = if j == 0 {
                if p.reading {
                    Kind::Speech
                } else if !callees.is_empty() && rng.chance(30) {
                    Kind::Recursive(*rng.pick(&callees))
                } else {
                    Kind::Neutral
                }
            } else {
                match rng.below(100) {
                    0..=39 => Kind::Speech,
                    40..=59 => Kind::Neutral,
                    60..=79 if !callees.is_empty() => Kind::Recursive(*rng.pick(&callees)),
                    60..=89 => Kind::Tick,
                    _ => Kind::Ask,
                }
            };
            p.kinds.push(kind);
        }
    }
    // Every sub is called from some DM above it.
    for j in 1..n {
        let called = plans
            .iter()
            .take(j)
            .any(|p| p.kinds.contains(&Kind::Recursive(j)));
        if !called {
            let i = rng.below(j);
            let at = rng.range(1, plans[i].kinds.len());
            plans[i].kinds.insert(at, Kind::Recursive(j));
        }
    }
    plans
}

// ------------------------------------------------------------------ text

/// What an arc may use: variables bound by its expectation (or the
/// situation's id, in_arg, a call's result), with the numeric ones (small
/// non-negative integers, safe as countdown starts) apart.
#[derive(Clone, Default)]
struct Scope {
    terms: Vec<String>,
    nums: Vec<String>,
    /// The in_arg variable of the situation.
    input: Option<String>,
    /// The out_arg variable of the situation, when out_arg is one.
    out: Option<String>,
    /// Speech arcs may reset the guard counter `n`.
    reads: bool,
}

struct Gen<'a> {
    plans: &'a [Plan],
    me: usize,
    rng: &'a mut Rng,
    vars: usize,
    /// Inputs (of [`VOCABULARY`]) that meet the expectations made so far.
    inputs: Vec<&'static str>,
}

impl<'a> Gen<'a> {
    fn new(plans: &'a [Plan], me: usize, rng: &'a mut Rng) -> Gen<'a> {
        Gen {
            plans,
            me,
            rng,
            vars: 0,
            inputs: Vec::new(),
        }
    }

    fn plan(&self) -> &'a Plan {
        &self.plans[self.me]
    }

    /// What every situation of the DM sees: the DM's parameters (`Hp` is
    /// bound by the call, `Hr` only by a final's `diag_mod`).
    fn scope(&self) -> Scope {
        let terms = match self.plan().arity {
            0 => vec![],
            1 => vec!["Hr".to_owned()],
            _ => vec!["Hp".to_owned(), "Hp".to_owned(), "Hr".to_owned()],
        };
        Scope {
            terms,
            ..Scope::default()
        }
    }

    fn var(&mut self, prefix: &str) -> String {
        self.vars += 1;
        format!("{prefix}{}", self.vars)
    }

    /// The whole `diag_mod(...)` clause.
    fn dm(&mut self) -> String {
        let p = self.plan();
        let head = match p.arity {
            0 => p.name.clone(),
            1 => format!("{}(Hr)", p.name),
            _ => format!("{}(Hp, Hr)", p.name),
        };
        let mut situations = Vec::new();
        for j in 0..p.kinds.len() {
            match p.kinds[j] {
                Kind::Speech => {
                    let scope = self.scope();
                    situations.push(self.speech(j, format!("s{j}"), scope));
                }
                Kind::Ask => {
                    if self.rng.chance(40) {
                        let scope = self.scope();
                        situations.push(self.speech(j, format!("ask{j}(0)"), scope));
                    }
                    let k = self.var("K");
                    let mut scope = self.scope();
                    scope.terms.push(k.clone());
                    scope.nums.push(k.clone());
                    situations.push(self.speech(j, format!("ask{j}({k})"), scope));
                }
                Kind::Neutral => situations.push(self.neutral(j)),
                Kind::Recursive(c) => situations.push(self.recursive(j, c)),
                Kind::Tick => {
                    let (zero, step) = self.tick(j);
                    situations.push(zero);
                    situations.push(step);
                }
            }
        }
        for k in 0..p.finals.len() {
            situations.push(self.final_situation(k));
        }
        let mut locals = vec!["n ==> 0".to_owned()];
        if p.has_m {
            locals.push("m ==> 0".to_owned());
        }
        if p.has_l {
            locals.push("l ==> []".to_owned());
        }
        if p.has_v {
            locals.push("v ==> none".to_owned());
        }
        let at = self.rng.below(locals.len());
        locals.rotate_left(at);
        let text = format!(
            "% {} of a random program (tests/gen/random_dm.rs)\ndiag_mod({head},\n  [\n{}\n  ],\n  [ {} ]\n).\n",
            p.name,
            situations.join(",\n"),
            locals.join(", ")
        );
        mark_singletons(&text)
    }

    /// `in_arg`, `out_arg` and `prog` attributes (each optional) and the
    /// scope they give the arcs.
    fn pipe_attrs(
        &mut self,
        attrs: &mut Vec<String>,
        scope: &mut Scope,
        percent: u64,
        may_fail: bool,
    ) {
        if self.rng.chance(percent) {
            let v = self.var("In");
            if may_fail && self.rng.chance(2) {
                // A pattern the pipe rarely matches: skipped (D-8).
                attrs.push(format!("in_arg ==> w({v})"));
            } else {
                attrs.push(format!("in_arg ==> {v}"));
            }
            scope.terms.push(v.clone());
            scope.input = Some(v);
        }
        if self.rng.chance(percent) {
            let choice = self.rng.below(5);
            let out = match (choice, &scope.input) {
                (0 | 1, _) => {
                    let v = self.var("V");
                    scope.out = Some(v.clone());
                    v
                }
                (2, Some(i)) => format!("p({i})"),
                (3, _) if self.plan().has_m => "get(m, _)".to_owned(),
                _ => "piped".to_owned(),
            };
            attrs.push(format!("out_arg ==> {out}"));
        }
        if self.rng.chance(percent) {
            let mut prog = Vec::new();
            if let (Some(i), Some(o)) = (&scope.input, &scope.out) {
                if self.rng.chance(60) {
                    // prog binds the out_arg (D-10).
                    prog.push(format!("{o} = w({i})"));
                }
            }
            if self.plan().has_m && self.rng.chance(50) {
                prog.push("inc(m, _)".to_owned());
            }
            if prog.is_empty() || self.rng.chance(30) {
                prog.push("inc(g_count, _)".to_owned());
            }
            attrs.push(format!("prog ==> [{}]", prog.join(", ")));
        }
    }

    fn situation(attrs: &[String]) -> String {
        format!("    [ {}\n    ]", attrs.join(",\n      "))
    }

    fn speech(&mut self, j: usize, id: String, mut scope: Scope) -> String {
        let mut attrs = vec![format!("id ==> {id}"), "type ==> speech".to_owned()];
        self.pipe_attrs(&mut attrs, &mut scope, 35, self.me > 0 && j > 0);
        scope.reads = true;
        let n = if self.me == 0 && j == 0 {
            self.rng.range(2, 4)
        } else {
            self.rng.range(1, 4)
        };
        let mut atoms: Vec<&str> = vec!["a", "b", "c", "yes", "no", "stop"];
        let mut arcs = Vec::new();
        for a in 0..n {
            let mut s = scope.clone();
            let exp = self.expectation(&mut s, &mut atoms, a == 0);
            let mut action = self.action(&s);
            let start = self.me == 0 && j == 0;
            if a > 0 && !start && self.rng.chance(5) {
                // Not a number: an error (E7), when this arc is taken. `v`
                // is set first to what the global `g_log` holds (a list,
                // never a number, but `check` cannot know it): a local
                // never set from its non-number default, or set to a
                // constant that is not a number, is `check`'s E0242, and
                // the program would not compile (the error is the run's
                // to show).
                let extra = if self.plan().has_v {
                    vec![
                        "get(g_log, NotNum)".to_owned(),
                        "set(v, NotNum)".to_owned(),
                        "inc(v, _)".to_owned(),
                    ]
                } else {
                    vec!["inc(g_log, _)".to_owned()]
                };
                action = with_extra(action, extra);
            }
            let p = self.plan();
            let to_final = if exp == "stop" {
                60
            } else if self.me == 0 {
                5
            } else {
                25
            };
            let next = if a > 0 && !start && exp.starts_with("said(") && self.rng.chance(5) {
                // A situation named by the input (`said(a)` names none of
                // ours: an error, E8).
                exp["said(".len()..exp.len() - 1].to_owned()
            } else if start && exp != "stop" {
                // The task goes on past its first situation.
                let t = 1 + self.rng.below(p.kinds.len() - 1);
                self.target_text(t, &s)
            } else if self.rng.chance(to_final) {
                let k = self.rng.below(p.finals.len());
                self.target_text(p.kinds.len() + k, &s)
            } else {
                self.next(j, true, &s, &mut Vec::new())
            };
            arcs.push(format!("{exp} : {action} => {next}"));
        }
        attrs.push(format!(
            "arcs ==> [\n        {}\n      ]",
            arcs.join(",\n        ")
        ));
        Self::situation(&attrs)
    }

    /// An expectation of a speech arc; notes inputs that meet it. Only a
    /// `first` arc may expect anything (a bare variable), so that the later
    /// arcs still win when they match (the last matching arc wins, D-14).
    fn expectation(&mut self, s: &mut Scope, atoms: &mut Vec<&'static str>, first: bool) -> String {
        loop {
            match self.rng.below(100) {
                0..=37 if !atoms.is_empty() => {
                    let i = self.rng.below(atoms.len());
                    let atom = atoms.remove(i);
                    self.inputs.push(atom);
                    return atom.to_owned();
                }
                38..=51 => {
                    let x = self.var("X");
                    s.terms.push(x.clone());
                    let said = *self.rng.pick(&["said(a)", "said(b)", "said(hello)"]);
                    self.inputs.push(said);
                    return format!("said({x})");
                }
                52..=62 => {
                    let x = self.var("N");
                    s.terms.push(x.clone());
                    s.nums.push(x.clone());
                    self.num_inputs();
                    return format!("num({x})");
                }
                63..=70 => {
                    let x = self.var("X");
                    s.terms.push(x.clone());
                    return if self.rng.chance(50) {
                        self.inputs.push(*self.rng.pick(&["[a,b]", "[a,c]"]));
                        format!("[a, {x}]")
                    } else {
                        self.inputs.push("[c,b]");
                        format!("[{x}, b]")
                    };
                }
                71..=74 => {
                    self.inputs.push("[a,b]");
                    return "[a, b]".to_owned();
                }
                75..=80 if s.input.is_some() => {
                    // The pipe's value, often `none` or `p(none)`.
                    self.inputs.push("none");
                    self.inputs.push("p(none)");
                    return s.input.clone().unwrap();
                }
                81..=88 if s.out.is_some() => {
                    // The arc binds the situation's out_arg (D-11).
                    let o = s.out.clone().unwrap();
                    return if self.rng.chance(50) {
                        self.inputs.push("said(b)");
                        format!("said({o})")
                    } else {
                        s.nums.push(o.clone());
                        self.num_inputs();
                        format!("num({o})")
                    };
                }
                89..=91 if self.plan().has_v => {
                    self.inputs.push("none");
                    return "get(v, _)".to_owned();
                }
                92..=94 if self.plan().has_m => {
                    // Its update is discarded (D-12, E17).
                    let x = self.var("M");
                    s.terms.push(x.clone());
                    self.inputs.push("1");
                    self.inputs.push("2");
                    return format!("inc(m, {x})");
                }
                95..=99 if first => {
                    // Meets every input.
                    let x = self.var("X");
                    s.terms.push(x.clone());
                    return x;
                }
                _ => {}
            }
        }
    }

    fn num_inputs(&mut self) {
        let from = self.rng.below(3);
        self.inputs
            .extend_from_slice(&["num(0)", "num(1)", "num(2)", "num(3)"][from..from + 2]);
    }

    /// A term to show: a bound variable or a constant.
    fn term(&mut self, s: &Scope) -> String {
        if !s.terms.is_empty() && self.rng.chance(70) {
            self.rng.pick(&s.terms).clone()
        } else {
            (*self.rng.pick(&["a", "b", "hello", "'well done'", "7"])).to_owned()
        }
    }

    fn num(&mut self, s: &Scope, max: usize) -> String {
        if !s.nums.is_empty() && self.rng.chance(60) {
            self.rng.pick(&s.nums).clone()
        } else {
            self.rng.range(0, max).to_string()
        }
    }

    /// An action: a list of 0–4 items, or a single term.
    fn action(&mut self, s: &Scope) -> String {
        let p = self.plan();
        if self.rng.chance(12) {
            return (*self.rng.pick(&["empty", "say(hi)", "screen('Good Bye')"])).to_owned();
        }
        let mut items: Vec<String> = Vec::new();
        for _ in 0..self.rng.range(0, 3) {
            match self.rng.below(16) {
                0 => {
                    let t = self.term(s);
                    items.push(format!("say({t})"));
                }
                1 => items.push("screen('hello there')".to_owned()),
                2 => items.push("inc(n, _)".to_owned()),
                3 if p.has_m => {
                    let x = self.var("M");
                    items.push(format!("inc(m, {x})"));
                }
                4 if p.has_m => {
                    let n = self.num(s, 3);
                    items.push(format!("set(m, {n})"));
                }
                5 if p.has_v => {
                    let t = self.term(s);
                    items.push(format!("set(v, {t})"));
                }
                6 if p.has_v => {
                    let x = self.var("G");
                    items.push(format!("get(v, {x})"));
                    items.push(format!("seen({x})"));
                }
                7 if p.has_l => {
                    let t = self.term(s);
                    let (a, b) = (self.var("L"), self.var("L"));
                    items.push(format!("get(l, {a})"));
                    items.push(format!("append({a}, [{t}], {b})"));
                    items.push(format!("set(l, {b})"));
                }
                8 => {
                    let t = self.term(s);
                    let (a, b) = (self.var("Gl"), self.var("Gl"));
                    items.push(format!("get(g_log, {a})"));
                    items.push(format!("append({a}, [{t}], {b})"));
                    items.push(format!("set(g_log, {b})"));
                }
                9 => items.push("inc(g_count, _)".to_owned()),
                10 => {
                    let c = self.condition(s);
                    let (a, b) = (self.term(s), self.term(s));
                    items.push(format!("({c} -> big({a}) ; otherwise -> small({b}))"));
                }
                11 if !s.nums.is_empty() => {
                    let n = self.rng.pick(&s.nums).clone();
                    let x = self.var("S");
                    items.push(format!("{x} is {n} + 1"));
                    items.push(format!("succ({x})"));
                }
                12 if s.reads => items.push("set(n, 0)".to_owned()),
                13 => {
                    let t = self.term(s);
                    let x = self.var("U");
                    items.push(format!("{x} = pair({t}, b)"));
                }
                14 => {
                    let t = self.term(s);
                    items.push(format!("member({t}, [a, b, 2])"));
                }
                _ => {
                    let t = self.term(s);
                    items.push(format!("done({t})"));
                }
            }
        }
        format!("[{}]", items.join(", "))
    }

    /// A condition for `(C -> A ; otherwise -> B)`.
    fn condition(&mut self, s: &Scope) -> String {
        loop {
            match self.rng.below(5) {
                0 if self.plan().has_m => {
                    let k = self.rng.range(1, 3);
                    return format!("get(m, _) >= {k}");
                }
                1 if !s.nums.is_empty() => {
                    let n = self.rng.pick(&s.nums).clone();
                    let k = self.rng.range(1, 3);
                    return format!("{n} >= {k}");
                }
                2 if !s.terms.is_empty() => {
                    let t = self.rng.pick(&s.terms).clone();
                    return format!("{t} == a");
                }
                3 => return "get(n, _) > 1".to_owned(),
                4 => return "get(g_count, _) < 2".to_owned(),
                _ => {}
            }
        }
    }

    /// A next situation of node `j`: anywhere when `any`, else forwards
    /// (or a guarded back edge, whose `inc(n, C)` goes to `extra`).
    fn next(&mut self, j: usize, any: bool, s: &Scope, extra: &mut Vec<String>) -> String {
        let situations = self.plan().kinds.len();
        let total = situations + self.plan().finals.len();
        // Forwards, mostly to a situation rather than straight to a final.
        let stay = if self.me == 0 { 85 } else { 60 };
        let forward = move |rng: &mut Rng| {
            let end = if j + 1 < situations && rng.chance(stay) {
                situations
            } else {
                total
            };
            j + 1 + rng.below(end - j - 1)
        };
        let r = self.rng.below(100);
        if !any && r < 25 {
            let c = self.var("C");
            let k = self.rng.range(1, 3);
            extra.push(format!("inc(n, {c})"));
            let f = forward(self.rng);
            let back = self.rng.range(0, j);
            let (f, b) = (self.target_text(f, s), self.target_text(back, s));
            return format!("({c} >= {k} -> {f} ; otherwise -> {b})");
        }
        let pick = |rng: &mut Rng| {
            if any {
                // Mostly a situation; finals are chosen apart (speech).
                let n = if rng.chance(80) { situations } else { total };
                rng.below(n)
            } else {
                forward(rng)
            }
        };
        if r >= 85 {
            let c = self.condition(s);
            let (a, b) = (pick(self.rng), pick(self.rng));
            let (a, b) = (self.target_text(a, s), self.target_text(b, s));
            return format!("({c} -> {a} ; otherwise -> {b})");
        }
        let t = pick(self.rng);
        self.target_text(t, s)
    }

    /// How to name situation (or final) `t` as a next situation.
    fn target_text(&mut self, t: usize, s: &Scope) -> String {
        let p = self.plan();
        if t >= p.kinds.len() {
            let k = t - p.kinds.len();
            if p.finals[k] {
                let a = self.term(s);
                return format!("got{k}({a})");
            }
            return format!("f{k}");
        }
        match p.kinds[t] {
            Kind::Tick if t % 2 == 1 => {
                // A list walked by a pattern id, sometimes with an open tail.
                let items: Vec<String> = (0..self.rng.range(0, 3)).map(|_| self.term(s)).collect();
                let tail = if self.rng.chance(20) { "|_" } else { "" };
                format!("tick{t}([{}{tail}])", items.join(", "))
            }
            Kind::Tick => {
                let n = self.num(s, 3);
                format!("tick{t}({n})")
            }
            Kind::Ask => {
                let n = self.num(s, 2);
                format!("ask{t}({n})")
            }
            _ => format!("s{t}"),
        }
    }

    fn neutral(&mut self, j: usize) -> String {
        let mut attrs = vec![format!("id ==> s{j}"), "type ==> neutral".to_owned()];
        let mut scope = self.scope();
        self.pipe_attrs(&mut attrs, &mut scope, 30, self.me > 0 && j > 0);
        let mut extra = Vec::new();
        let next = self.next(j, false, &scope, &mut extra);
        let action = with_extra(self.action(&scope), extra);
        attrs.push(format!(
            "arcs ==> [\n        empty : {action} => {next}\n      ]"
        ));
        Self::situation(&attrs)
    }

    fn tick(&mut self, j: usize) -> (String, String) {
        let scope = self.scope();
        let mut extra = Vec::new();
        let next = self.next(j, false, &scope, &mut extra);
        let action = with_extra(self.action(&scope), extra);
        if j % 2 == 1 {
            return self.walk(j, action, next);
        }
        let zero = Self::situation(&[
            format!("id ==> tick{j}(0)"),
            "type ==> neutral".to_owned(),
            format!("arcs ==> [\n        empty : {action} => {next}\n      ]"),
        ]);
        let n = self.var("T");
        let m = self.var("T");
        let mut attrs = vec![
            format!("id ==> tick{j}({n})"),
            "type ==> neutral".to_owned(),
        ];
        if self.rng.chance(40) {
            attrs.push("prog ==> [inc(g_count, _)]".to_owned());
        }
        let say = if self.rng.chance(50) {
            format!(", ({m} > 0 -> say(more) ; otherwise -> say(last))")
        } else {
            String::new()
        };
        attrs.push(format!(
            "arcs ==> [\n        empty : [{m} is {n} - 1{say}] => tick{j}({m})\n      ]"
        ));
        (zero, Self::situation(&attrs))
    }

    /// `tickJ([])` then `tickJ([H|T])`: a list walked by a situation whose
    /// id is a pattern (not only fresh variables and constants).
    fn walk(&mut self, j: usize, action: String, next: String) -> (String, String) {
        let zero = Self::situation(&[
            format!("id ==> tick{j}([])"),
            "type ==> neutral".to_owned(),
            format!("arcs ==> [\n        empty : {action} => {next}\n      ]"),
        ]);
        let h = self.var("H");
        let t = self.var("T");
        let mut attrs = vec![
            format!("id ==> tick{j}([{h}|{t}])"),
            "type ==> neutral".to_owned(),
        ];
        if self.rng.chance(10) {
            attrs.push(format!("in_arg ==> {h}"));
        }
        attrs.push(format!(
            "arcs ==> [\n        empty : say({h}) => tick{j}({t})\n      ]"
        ));
        (zero, Self::situation(&attrs))
    }

    fn recursive(&mut self, j: usize, c: usize) -> String {
        let callee = &self.plans[c];
        let mut attrs = vec![format!("id ==> s{j}"), "type ==> recursive".to_owned()];
        let mut scope = self.scope();
        self.pipe_attrs(&mut attrs, &mut scope, 30, self.me > 0 && j > 0);
        let call = match callee.arity {
            0 => callee.name.clone(),
            1 => {
                let r = self.var("R");
                scope.terms.push(r.clone());
                format!("{}({r})", callee.name)
            }
            _ => {
                let r = self.var("R");
                let p = self.plan();
                let arg = match (&scope.input, self.rng.below(5)) {
                    (Some(i), 0) => i.clone(),
                    (_, 1) => "b".to_owned(),
                    // Evaluated, with the locals read-only (D-22).
                    (_, 2) if p.has_m => "get(m, _)".to_owned(),
                    (_, 3) if p.arity == 2 => "Hp".to_owned(),
                    _ => "a".to_owned(),
                };
                scope.terms.push(r.clone());
                format!("{}({arg}, {r})", callee.name)
            }
        };
        attrs.push(format!("embedded_dm ==> {call}"));
        // A callee that reads on entry makes this situation read too.
        let any = callee.reading;
        let mut finals: Vec<usize> = (0..callee.finals.len()).collect();
        for i in (1..finals.len()).rev() {
            let k = self.rng.below(i + 1);
            finals.swap(i, k);
        }
        if finals.len() > 1 && self.rng.chance(10) {
            // No exit arc for one final: an error when it is reached.
            finals.pop();
        }
        let mut arcs = Vec::new();
        for k in finals {
            let mut s = scope.clone();
            let mut patterns = Vec::new();
            if callee.finals[k] {
                if self.rng.chance(30) {
                    // Tried first (the first matching arc wins, D-22).
                    patterns.push((format!("got{k}(a)"), s.clone()));
                }
                let x = self.var("Y");
                s.terms.push(x.clone());
                patterns.push((format!("got{k}({x})"), s));
            } else {
                patterns.push((callee.final_id(k), s));
            }
            for (pattern, s) in patterns {
                let mut extra = Vec::new();
                let next = self.next(j, any, &s, &mut extra);
                let action = with_extra(self.action(&s), extra);
                arcs.push(format!("{pattern} : {action} => {next}"));
            }
        }
        attrs.push(format!(
            "arcs ==> [\n        {}\n      ]",
            arcs.join(",\n        ")
        ));
        Self::situation(&attrs)
    }

    fn final_situation(&mut self, k: usize) -> String {
        let p = self.plan();
        let mut scope = self.scope();
        let id = if p.finals[k] {
            let a = self.var("A");
            scope.terms.push(a.clone());
            format!("got{k}({a})")
        } else {
            format!("f{k}")
        };
        let mut attrs = vec![format!("id ==> {id}"), "type ==> final".to_owned()];
        if self.rng.chance(40) {
            let v = self.var("In");
            if self.me > 0 && self.rng.chance(8) {
                // Matches only a pipe `w(_)`: else skipped (D-8).
                attrs.push(format!("in_arg ==> w({v})"));
            } else {
                attrs.push(format!("in_arg ==> {v}"));
            }
            scope.terms.push(v);
        }
        if self.rng.chance(40) {
            let t = self.term(&scope);
            attrs.push(format!("out_arg ==> r({t})"));
        }
        if self.rng.chance(20) {
            attrs.push("prog ==> [inc(g_count, _)]".to_owned());
        }
        if p.arity > 0 && self.rng.chance(75) {
            let value = if self.rng.chance(5) {
                "zz".to_owned()
            } else {
                self.term(&scope)
            };
            let dm = if p.arity == 1 {
                format!("{}({value})", p.name)
            } else if self.rng.chance(10) {
                // Not the caller's argument unless it is `zz`: an error (E9).
                format!("{}(zz, {value})", p.name)
            } else {
                format!("{}(Hp, {value})", p.name)
            };
            attrs.push(format!("diag_mod ==> {dm}"));
        }
        Self::situation(&attrs)
    }
}

/// Appends `extra` items to a list action (or makes one).
fn with_extra(action: String, extra: Vec<String>) -> String {
    if extra.is_empty() {
        return action;
    }
    match action.strip_prefix('[').and_then(|a| a.strip_suffix(']')) {
        Some("") => format!("[{}]", extra.join(", ")),
        Some(inner) => format!("[{inner}, {}]", extra.join(", ")),
        None => format!("[{action}, {}]", extra.join(", ")),
    }
}

/// Prefixes with `_` every named variable that occurs once in the clause
/// (so the checker has no singleton warnings to give).
fn mark_singletons(text: &str) -> String {
    let mut counts: Vec<(String, usize)> = Vec::new();
    each_var(text, |name| {
        match counts.iter_mut().find(|(n, _)| n == name) {
            Some(e) => e.1 += 1,
            None => counts.push((name.to_owned(), 1)),
        }
    });
    let mut out = String::with_capacity(text.len());
    let mut last = 0;
    each_var_span(text, |start, end| {
        out.push_str(&text[last..start]);
        let name = &text[start..end];
        if counts.iter().any(|(n, c)| n == name && *c == 1) {
            out.push('_');
        }
        out.push_str(name);
        last = end;
    });
    out.push_str(&text[last..]);
    out
}

fn each_var(text: &str, mut f: impl FnMut(&str)) {
    each_var_span(text, |a, b| f(&text[a..b]));
}

/// Calls `f` with the byte span of every variable name starting with an
/// upper-case letter, outside quoted atoms and `%` comments.
fn each_var_span(text: &str, mut f: impl FnMut(usize, usize)) {
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'\'' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'\'' {
                i += 1;
            }
            i += 1;
        } else if c == b'%' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if c.is_ascii_alphanumeric() || c == b'_' {
            let start = i;
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            if c.is_ascii_uppercase() {
                f(start, i);
            }
        } else {
            i += 1;
        }
    }
}
