//! Snapshots of generated code (prettyplease-formatted): a change to the
//! code generator reads as a diff of Rust (`cargo insta review`).

use sitlog_compiler::{check, codegen, ir, load};

fn generate(files: &[(&str, &str)]) -> String {
    let (program, diags) = load::load_sources(files);
    let (result, diags) = check::check(program, diags);
    let checked = match result {
        Ok(c) => c,
        Err(_) => panic!("does not check: {diags:#?}"),
    };
    let ir = ir::lower(&checked);
    codegen::generate_file(&ir, "small.dm")
}

const SMALL: &str = r#"
diag_mod(main,
  [
    [ id ==> is,
      type ==> speech,
      in_arg ==> In,
      out_arg ==> V,
      arcs ==> [
        num(V) : [got(In, V), set(count, 1)] => step(V),
        stop : screen('Good bye') => fs
      ]
    ],
    [ id ==> step(0),
      type ==> neutral,
      arcs ==> [ empty : [done] => fs ]
    ],
    [ id ==> step(N),
      type ==> neutral,
      arcs ==> [ empty : [M is N - 1] => step(M) ]
    ],
    [ id ==> fs,
      type ==> final,
      in_arg ==> W,
      out_arg ==> result(W)
    ]
  ],
  [count ==> 0]
).
"#;

#[test]
fn small_dm() {
    insta::assert_snapshot!(generate(&[
        ("small.dm", SMALL),
        ("global_vars.pl", "total ==> [a, 2.5].\n")
    ]));
}

#[test]
fn generation_is_deterministic() {
    let files = [("small.dm", SMALL)];
    assert_eq!(generate(&files), generate(&files));
}

#[test]
fn names_are_valid_identifiers() {
    // Atoms that are keywords, symbols or collide after mangling.
    let src = r#"
diag_mod('type',
  [ [ id ==> 'self', type ==> neutral, arcs ==> [ empty : ['a b', 'a_b', 'A-B', [], '$x'(-3, -0.0, 123456789012345678901234567890)] => 'fn' ] ],
    [ id ==> 'fn', type ==> final ],
    [ id ==> X, type ==> final ],
    [ id ==> exit, type ==> final ],
    [ id ==> situation, type ==> final ] ],
  []).
"#;
    let text = generate(&[("kw.dm", src)]);
    // It parses as Rust (generate_file formats it through syn).
    assert!(text.contains("pub mod dm_type"), "{text}");
    // The situation with a variable id: its row, by its template.
    assert!(
        text.contains("SitRow::template(Kind::Final, None, 5, 7)"),
        "{text}"
    );
    // Situations named like the module's own functions (`exit`: the
    // original's robocup_2015) get functions of their own.
    for f in ["fn run_exit_sit(", "fn run_situation_sit("] {
        assert!(text.contains(f), "{f}\n{text}");
    }
}

/// The tutorial's generated code (`sitlogc build --emit rust
/// dms/examples/tutorial`): what a reader of the guide sees.
#[test]
fn tutorial() {
    // Loaded by a relative path (tests run in the crate's directory): the
    // locations in doc comments are then the same text in any clone, so
    // the formatter wraps the same lines wherever the clone is.
    let app = std::path::Path::new("../dms/examples/tutorial");
    let (checked, diags) = sitlog_compiler::check_path(app).expect("readable");
    let checked = checked.unwrap_or_else(|_| panic!("does not check: {diags:#?}"));
    let ir = ir::lower(&checked);
    let code = codegen::generate_file(&ir, "dms/examples/tutorial");
    insta::assert_snapshot!(code);
}

/// A behaviour-library DM as the home butler compiles it: `find`'s module
/// (its situation enum, its native frame and `match`, its term code),
/// cut from `sitlogc build --emit rust dms/apps/home`.
#[test]
fn behaviour_library_find() {
    let app = std::path::Path::new("../dms/apps/home");
    // `behaviors/...` read from the repository's dms/, as sitlogc embeds
    // it; the world's functions are the robot's (unresolved here).
    let library: &'static load::Library = Box::leak(Box::new(load::Library {
        roots: vec![load::LibraryRoot {
            what: "the repository's dms/".to_owned(),
            files: load::LibraryFiles::Dir("../dms".into()),
        }],
    }));
    let options = check::CheckOptions {
        library: Some(library),
        unresolved_as_warnings: true,
        ..Default::default()
    };
    let (checked, diags) = sitlog_compiler::check_path_opts(app, options).expect("readable");
    let checked = checked.unwrap_or_else(|_| panic!("does not check: {diags:#?}"));
    let ir = ir::lower(&checked);
    let code = codegen::generate_file(&ir, "dms/apps/home");
    let start = code
        .find("pub mod dm_find {")
        .expect("the home butler compiles find");
    // The module ends at the first line that closes it at column 0.
    let len = code[start..].find("\n}\n").expect("the module ends") + 3;
    insta::assert_snapshot!(&code[start..start + len]);
}

/// A DM whose first situation names its parameter (`q(A)` in `ask(A)`),
/// called with the argument unbound (`ask(_X)`): the parameter is `term`,
/// so `q` is code on terms and the frame holds the parameter unconverted
/// (`cx.param`, not the checked `param_as`, which an unbound variable
/// fails: the DM would then run wholly on the machine).
#[test]
fn a_term_parameter_linked_into_the_first_situation_is_not_converted() {
    let src = r#"
diag_mod(main,
  [ [ id ==> s, type ==> recursive, embedded_dm ==> ask(_X), arcs ==> [ done(_) : empty => fin ] ],
    [ id ==> fin, type ==> final ] ],
  []).
diag_mod(ask(A),
  [ [ id ==> q(A), type ==> neutral, arcs ==> [ empty : [N is 1 + 1] => r(N) ] ],
    [ id ==> r(M), type ==> neutral, arcs ==> [ empty : [K is M + 1] => done(K) ] ],
    [ id ==> done(_), type ==> final ] ],
  []).
"#;
    let text = generate(&[("unbound.dm", src)]);
    let ask = text.split("pub mod dm_ask").nth(1).expect("ask's module");
    assert!(ask.contains("let p0 = cx.param(0).map(Ground)?;"), "{ask}");
    assert!(!ask.contains("param_as"), "{ask}");
    // Its other situations are native all the same (`r(M)`, `done(_)`).
    assert!(ask.contains("Nat::S1 { r2 } =>"), "{ask}");
}

/// The `'sel` blocks of `code` (each from `'sel: {` to its closing brace).
fn sel_blocks(code: &str) -> Vec<&str> {
    let mut blocks = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("'sel: {") {
        let from = &rest[at..];
        let mut depth = 0;
        let mut end = from.len();
        for (k, c) in from.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        blocks.push(&from[..end]);
        rest = &from[end..];
    }
    blocks
}

/// Every `let fk<N> = r<N>;` (the visit's own cell tail taken by move) in
/// `code` is followed by no test before its `break 'sel`: a test that can
/// still fail would fall through to a later candidate or the hand-over,
/// which read the moved register (E0505, issue 37, `review18` finding 1).
fn assert_moves_last(code: &str) {
    let moves = moved_tails(code);
    for &at in &moves {
        let after = &code[at..];
        let upto = after.find("break 'sel").expect("the variant follows");
        assert!(
            !after[..upto].contains("if "),
            "a test after the move:\n{}",
            &after[..upto]
        );
    }
    assert!(!moves.is_empty(), "no tail moved:\n{code}");
}

/// Where `code` moves a cell tail into a candidate (`let fk<N> = r<N>;`).
fn moved_tails(code: &str) -> Vec<usize> {
    code.match_indices("let fk")
        .filter(|&(at, _)| {
            let line = code[at..].lines().next().unwrap();
            let (x, e) = line
                .trim_start_matches("let ")
                .trim_end_matches(';')
                .split_once(" = ")
                .unwrap_or_default();
            e.strip_prefix('r') == x.strip_prefix("fk")
        })
        .map(|(at, _)| at)
        .collect()
}

/// Two lists walked in step (`step([X|Xs], [Y|Ys], Acc)`): the visit's own
/// cell tail is moved into the next situation only after the test of the
/// second list, so `[]`/`[H|T]` of lists of different lengths falls through
/// to the hand-over with the register intact (`nlock18`, issue 37).
#[test]
fn two_lists_walked_in_step() {
    let src = r#"
diag_mod(main(Xs, Ys),
  [ [ id ==> s, type ==> recursive, embedded_dm ==> dot(Xs, Ys),
      arcs ==> [ sum(_) : empty => fin, uneven : empty => fin ] ],
    [ id ==> fin, type ==> final ] ],
  []).
diag_mod(dot(Xs, Ys),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => step(Xs, Ys, 0) ] ],
    [ id ==> step([], [], Acc), type ==> neutral, arcs ==> [ empty : empty => sum(Acc) ] ],
    [ id ==> step([X|Xs1], [Y|Ys1], Acc), type ==> neutral,
      arcs ==> [ empty : [Acc1 is Acc + X * Y] => step(Xs1, Ys1, Acc1) ] ],
    [ id ==> sum(_), type ==> final ],
    [ id ==> uneven, type ==> final ] ],
  []).
"#;
    let text = generate(&[("lockstep.dm", src)]);
    let dot = text.split("pub mod dm_dot").nth(1).expect("dot's module");
    assert_moves_last(dot);
    let sel = sel_blocks(dot)
        .into_iter()
        .find(|b| !moved_tails(b).is_empty() && b.contains("nat_hand_over"))
        .expect("a selection that moves the tail and may hand over");
    insta::assert_snapshot!(sel);
}

/// Three lists in step, the cell candidate first and the list walked by
/// the visit's own cell not the first argument, then `[]`s, then a
/// catch-all: the move still comes after every test of its candidate.
#[test]
fn three_lists_walked_in_step_any_order() {
    let src = r#"
diag_mod(main(As, Bs, Cs),
  [ [ id ==> s, type ==> recursive, embedded_dm ==> zip3(As, Bs, Cs),
      arcs ==> [ done(_) : empty => fin, odd : empty => fin ] ],
    [ id ==> fin, type ==> final ] ],
  []).
diag_mod(zip3(As, Bs, Cs),
  [ [ id ==> begin, type ==> neutral, arcs ==> [ empty : empty => z(0, As, Bs, Cs) ] ],
    [ id ==> z(N, [_|As1], [_|Bs1], [_|Cs1]), type ==> neutral,
      arcs ==> [ empty : [N1 is N + 1] => z(N1, As1, Bs1, Cs1) ] ],
    [ id ==> z(N, [], [], []), type ==> neutral, arcs ==> [ empty : empty => done(N) ] ],
    [ id ==> z(_, _, _, _), type ==> neutral, arcs ==> [ empty : empty => odd ] ],
    [ id ==> done(_), type ==> final ],
    [ id ==> odd, type ==> final ] ],
  []).
"#;
    let text = generate(&[("zip3.dm", src)]);
    let zip = text.split("pub mod dm_zip3").nth(1).expect("zip3's module");
    assert_moves_last(zip);
}

/// Plain Prolog user functions compiled to Rust (helper `nrs22`, issue
/// 37): `classify/1` (guards, a cut then `fail`, `is`, a cut inside an
/// if-then-else) and `pick/2` (list head patterns, `=`, `\==`, the last
/// assignment winning) of `tests/typed/nrs22`, each with its fingerprint,
/// cut from `sitlogc build --emit rust tests/typed/nrs22`.
#[test]
fn plain_functions_compiled_to_rust() {
    let app = std::path::Path::new("../tests/typed/nrs22");
    let (checked, diags) = sitlog_compiler::check_path(app).expect("readable");
    let checked = checked.unwrap_or_else(|_| panic!("does not check: {diags:#?}"));
    let ir = ir::lower(&checked);
    let code = codegen::generate_file(&ir, "tests/typed/nrs22");
    let start = code
        .find("    pub const FORM0: &str")
        .expect("classify/1 compiled");
    let end = code
        .find("    pub const FORM2: &str")
        .expect("diff/2 compiled");
    insta::assert_snapshot!(&code[start..end]);
}
