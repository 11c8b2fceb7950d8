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
