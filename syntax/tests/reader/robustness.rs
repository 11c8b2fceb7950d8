//! Bad and extreme input: never a panic, never a stack overflow, and a
//! clear error where the text is wrong.

use sitlog_syntax::{
    read_clauses, read_clauses_bytes, read_term, source_from_bytes, writeq, Clause, SyntaxError,
};

/// Reads `src` as one term, prints it, reads the print, and checks the terms agree.
fn round_trip(src: &str) -> Clause {
    let clause = read_term(src).unwrap_or_else(|e| panic!("{}: {e:?}", &src[..src.len().min(80)]));
    let printed = writeq(&clause, clause.root);
    let again = read_term(&format!("{printed} .")).unwrap_or_else(|e| {
        panic!(
            "printed text does not read back: {}: {e:?}",
            &printed[..printed.len().min(200)]
        )
    });
    assert!(
        clause.is_variant_of(&again),
        "round trip changed {}",
        &printed[..printed.len().min(200)]
    );
    clause
}

fn one_error(src: &str) -> SyntaxError {
    let (clauses, mut errors) = read_clauses(src);
    assert!(clauses.is_empty(), "{src:?} read a clause");
    assert_eq!(errors.len(), 1, "{src:?}: {errors:?}");
    errors.remove(0)
}

#[test]
fn empty_and_layout_only_inputs() {
    for src in [
        "",
        " ",
        "\n\n",
        "% only a comment",
        "/* c */",
        "\u{FEFF}",
        "\t% a\r\n% b\n",
    ] {
        let (clauses, errors) = read_clauses(src);
        assert!(clauses.is_empty() && errors.is_empty(), "{src:?}");
    }
    let e = read_term("").unwrap_err();
    assert!(e.incomplete);
}

#[test]
fn non_utf8_input_is_rejected_at_the_first_bad_byte() {
    let bytes = b"foo(a).\nbar(\xff\xfe).\n";
    let e = source_from_bytes(bytes).unwrap_err();
    assert_eq!(e.span.start, 12);
    assert!(e.message.contains("byte offset 12"), "{}", e.message);
    assert!(e.message.contains("0xFF"), "{}", e.message);
    assert_eq!(e.line_col_bytes(bytes), (2, 5));
    let (clauses, errors) = read_clauses_bytes(bytes);
    assert!(clauses.is_empty());
    assert_eq!(errors.len(), 1);
    // A truncated multi-byte character at the very end.
    let e = source_from_bytes(b"a('\xc3").unwrap_err();
    assert_eq!(e.span.start, 3);
    let (clauses, errors) = read_clauses_bytes("é(x).".as_bytes());
    assert_eq!((clauses.len(), errors.len()), (1, 0));
}

#[test]
fn unterminated_tokens() {
    for (src, what) in [
        ("a('abc).", "unterminated quoted atom"),
        ("a(\"abc).", "unterminated string"),
        ("a(`abc).", "unterminated back-quoted string"),
        ("a. /* never closed", "unterminated block comment"),
        ("a(b) /* never closed", "unterminated block comment"),
        ("x :- y, 0'", "incomplete character code"),
    ] {
        let (_, errors) = read_clauses(src);
        assert!(
            errors.iter().any(|e| e.message.contains(what)),
            "{src:?}: {errors:?}"
        );
    }
    let e = one_error("'abc");
    assert!(e.incomplete);
    assert_eq!(e.span.start, 0);
}

#[test]
fn missing_final_end() {
    let (clauses, errors) = read_clauses("a.\nb(c)");
    assert_eq!(clauses.len(), 1);
    assert_eq!(errors.len(), 1);
    assert!(errors[0].message.contains("missing `.`"), "{errors:?}");
    assert!(errors[0].incomplete);
    // read_term does not need the end.
    assert!(read_term("b(c)").is_ok());
}

#[test]
fn priority_clash_is_reported_where_it_happens() {
    let src = "x :- a = b = c.";
    let e = one_error(src);
    assert!(e.message.contains("priority clash"), "{e:?}");
    assert_eq!(&src[e.span.range()], "=");
    assert_eq!(e.span.start, 11);
    let e = one_error("k ==> e : a => n => m.");
    assert!(e.message.contains("priority clash"));
}

#[test]
fn trailing_comma_behind_a_comment_is_named() {
    let e = one_error("[a, % note\n].");
    assert_eq!(e.help.as_deref(), Some("remove the trailing `,`"));
}

const DEEP: usize = 100_000;

/// Nesting depth for one kind of nesting: 100 000 for every kind in release
/// builds (`cargo test --release`); debug builds (CI) run 100 000 for one
/// kind of each group and 10 000 for the others, which take the same paths.
fn depth(representative: bool) -> usize {
    if representative || !cfg!(debug_assertions) || std::env::var_os("SITLOG_DEEP_FULL").is_some() {
        DEEP
    } else {
        DEEP / 10
    }
}

#[test]
fn deep_brackets() {
    let n = DEEP;
    round_trip(&format!("{}a{}", "f(".repeat(n), ")".repeat(n)));
    round_trip(&format!("{}a{}", "[".repeat(n), "]".repeat(n)));
    round_trip(&format!("{}a{}", "(".repeat(n), ")".repeat(n)));
    round_trip(&format!("{}a{}", "{".repeat(n), "}".repeat(n)));
    round_trip(&format!("{}a{}", "[a|".repeat(n), "]".repeat(n)));
    let n = depth(false);
    round_trip(&format!("{}a{}", "f(x, ".repeat(n), ")".repeat(n)));
    round_trip(&format!(
        "{}[]{}",
        "'hello world'([".repeat(n),
        "])".repeat(n)
    ));
}

#[test]
fn deep_prefix_operators() {
    for (i, op) in ["- ", "\\+ ", "- (", "\\ ", "+ ", ":- (", "\\+ ("]
        .into_iter()
        .enumerate()
    {
        let n = depth(i < 3);
        let close = if op.ends_with('(') { ")" } else { "" };
        round_trip(&format!("{}a{}", op.repeat(n), close.repeat(n)));
    }
    let n = depth(false);
    round_trip(&format!("{}1", "- ".repeat(n)));
    round_trip(&format!("{}1{}", "-(".repeat(n), ")".repeat(n)));
    // Alternating operators that need brackets at every level.
    round_trip(&format!(
        "{}a{}",
        "- (\\+ ".repeat(n / 2),
        ")".repeat(n / 2)
    ));
}

#[test]
fn deep_infix_operators() {
    // Right-nested xfy chains.
    for (i, op) in [",", "|", ";", "->", "^"].into_iter().enumerate() {
        round_trip(&format!("({})", vec!["a"; depth(i < 2)].join(op)));
    }
    // Left-nested yfx chains.
    for (i, op) in ["-", "+", "*", "/", " mod "].into_iter().enumerate() {
        round_trip(&vec!["a"; depth(i < 1)].join(op));
    }
    // xfx operators cannot chain: nest them with brackets on either side.
    for (i, op) in [":", "==>", "=>", "=", ":-", "is"].into_iter().enumerate() {
        let n = depth(i < 2);
        round_trip(&format!(
            "{}a{}",
            format!("a {op} (").repeat(n),
            ")".repeat(n)
        ));
        round_trip(&format!(
            "{}a{}",
            "(".repeat(n),
            format!(") {op} a").repeat(n)
        ));
    }
    // Right-nested yfx and left-nested xfy need brackets at every level.
    let n = depth(false);
    round_trip(&format!("{}a{}", "a - (".repeat(n), ")".repeat(n)));
    round_trip(&format!("{}a{}", "(".repeat(n), "), a".repeat(n)));
}

#[test]
fn long_flat_terms() {
    let n = 10 * depth(false);
    let c = round_trip(&format!("[{}]", vec!["a"; n].join(",")));
    assert_eq!(c.terms.proper_list(c.root).map(|l| l.len()), Some(n));
    round_trip(&format!("f({})", vec!["X"; n].join(",")));
}

#[test]
fn unbalanced_deep_input_is_an_error_not_a_crash() {
    let n = DEEP;
    for open in ["f(", "[", "(", "{", "- (", "[a|"] {
        let src = format!("{}a.", open.repeat(n));
        let (clauses, errors) = read_clauses(&src);
        assert!(clauses.is_empty());
        assert_eq!(errors.len(), 1, "{open}");
        assert!(
            !errors[0].labels.is_empty(),
            "{open}: names the unclosed bracket"
        );
    }
    let src = format!("a{}.", ")".repeat(n));
    assert!(!read_clauses(&src).1.is_empty());
}

/// About 50 MB of DM-like clauses, generated at run time.
fn big_text() -> String {
    let clause = "diag_mod(task(X, Y), [[id ==> is, type ==> neutral, arcs ==> \
                  [heard(X) : [say('Hello, this is a fairly long sentence'), tilt(-30.0)] => next(Y), \
                  error : empty => is]]], [tries ==> 0]). % comment\n";
    clause.repeat(50_000_000 / clause.len() + 1)
}

#[test]
#[ignore = "50 MB: slow in debug builds; run with --release -- --ignored"]
fn fifty_megabytes() {
    let src = big_text();
    assert!(src.len() >= 50_000_000);
    let t = std::time::Instant::now();
    let (clauses, errors) = read_clauses(&src);
    eprintln!(
        "50 MB of clauses: {} clauses in {:?}",
        clauses.len(),
        t.elapsed()
    );
    assert!(errors.is_empty());
    assert_eq!(clauses.len(), src.lines().count());
    // One single 50 MB term (a list of all those clauses' bodies).
    let body = src.replace(". % comment\n", ", ");
    let one = format!("[{}end].", body);
    let t = std::time::Instant::now();
    let (clauses, errors) = read_clauses(&one);
    eprintln!("one 50 MB term: {:?}", t.elapsed());
    assert!(errors.is_empty(), "{:?}", &errors[..1]);
    assert_eq!(clauses.len(), 1);
    let printed = writeq(&clauses[0], clauses[0].root);
    assert!(printed.len() > 40_000_000);
}

/// Inputs found by fuzzing (fuzz/): each must read without a panic, quickly,
/// every clause read must print and read back as the same term, and the
/// lexer's fast paths must agree with the grammar alone on it.
#[test]
fn fuzz_regressions() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).expect("fuzz_regressions folder") {
        let bytes = std::fs::read(entry.expect("entry").path()).expect("readable");
        let t = std::time::Instant::now();
        if let Ok(text) = std::str::from_utf8(&bytes) {
            if let Some(diff) = sitlog_syntax::fast_path_disagreement(text) {
                panic!("{diff}");
            }
        }
        let (clauses, _errors) = read_clauses_bytes(&bytes);
        for clause in &clauses {
            let printed = writeq(clause, clause.root);
            let again = read_term(&format!("{printed} .")).expect("printed text reads back");
            assert!(clause.is_variant_of(&again), "{printed}");
        }
        assert!(t.elapsed().as_secs() < 5, "slow input");
        n += 1;
    }
    assert!(n > 0);
}

/// A `\u`/`\U` escape cut short by a character of more than one byte
/// (fuzz/ `input`, issue 31: `'\ubbd\u{a0}'` panicked slicing the text
/// inside the character where the error's span ended): one error, its span
/// on character boundaries, covering the escape and the whole character.
#[test]
fn a_unicode_escape_cut_short_by_a_wide_character_is_an_error_on_character_boundaries() {
    for (src, shown) in [
        ("'\\ubbd\u{a0}'.", "\\ubbd\u{a0}"),
        ("\"\\U0001F60\u{e9}x\" .", "\\U0001F60\u{e9}"),
        ("'\\u\u{1F600}' .", "\\u\u{1F600}"),
    ] {
        let e = one_error(src);
        assert!(e.message.contains("hexadecimal digits"), "{src:?}: {e:?}");
        assert_eq!(src.get(e.span.range()), Some(shown), "{src:?}: {e:?}");
    }
}

/// Characters that start no token, a line of them (issue 31: 100 KB of
/// `\x01` took 14 s to check, each failed token costing the line's length):
/// one error at the first, the rest skipped with it, in linear time. A
/// quadratic path would make this test run for hours on 200 KB.
#[test]
fn a_line_of_characters_that_start_no_token_is_one_error_read_in_linear_time() {
    let mut chars: Vec<char> = (0u8..0x20)
        .filter(|b| !matches!(b, b'\t' | b'\n' | b'\r' | 0x0B | 0x0C))
        .map(char::from)
        .collect();
    chars.extend([
        '\u{7F}', '\u{85}', '\u{A4}', '\u{20AC}', '\u{0663}', '\u{0301}',
    ]);
    for c in chars {
        let src: String = std::iter::repeat_n(c, 200_000).collect();
        let (clauses, errors) = read_clauses(&src);
        assert!(clauses.is_empty());
        assert!(!errors.is_empty(), "U+{:04X}", c as u32);
        assert_eq!(errors[0].span.start, 0, "U+{:04X}", c as u32);
        let expected = if c.is_control() {
            format!("unexpected control character U+{:04X}", c as u32)
        } else {
            format!("unexpected character `{c}`")
        };
        assert_eq!(errors[0].message, expected);
    }
}

/// A line of 200 000 opening brackets (issue 31): the hint for a forgotten
/// closing bracket looked back from every bracket to its line's start,
/// quadratic in the line's length; now each byte is looked at once.
#[test]
fn a_long_line_of_unclosed_brackets_is_an_error_in_linear_time() {
    for open in ["[", "(", "{", "a("] {
        let src = open.repeat(200_000);
        let (clauses, errors) = read_clauses(&src);
        assert!(clauses.is_empty());
        assert!(!errors.is_empty(), "{open}");
    }
}
