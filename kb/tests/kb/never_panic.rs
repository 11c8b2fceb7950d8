//! Issue 23: any bytes as a KB file get a verdict, never a panic; a KB that
//! loads answers every service and takes every update without a panic.
//! (The cargo-fuzz target `kb` in fuzz/ runs the same property.)

use proptest::prelude::*;
use sitlog_kb::{Kb, SERVICES, UPDATES};

/// Every service and update on `kb`, with arguments from `names`.
fn exercise(kb: &Kb, names: &[&str]) {
    for (k, s) in SERVICES.iter().enumerate() {
        let mut args: Vec<String> = (0..s.arity - 1)
            .map(|i| names[(k + i) % names.len()].to_owned())
            .collect();
        args.push("Answer".into());
        let _ = kb.query(&format!("{}({})", s.name, args.join(",")));
    }
    for (k, u) in UPDATES.iter().enumerate() {
        let mut copy = kb.clone();
        let args: Vec<String> = (0..u.arity)
            .map(|i| names[(k + 2 * i) % names.len()].to_owned())
            .collect();
        if let Ok(clause) = sitlog_syntax::read_term(&format!("{}({})", u.name, args.join(","))) {
            if copy.update(&clause).is_ok() {
                Kb::parse(&copy.to_text(), "again").expect("a saved KB loads");
            }
        }
    }
}

const PIECES: &[&str] = &[
    "[", "]", "class(", ")", ",", "top", "none", "a", "b", "id=>", "=>", "=>>", "[]", "not(", "p",
    "1", "0", "2", ".", " ", "\n", "\u{e9}", "\u{ff}", "'q'", "X", "[[", "]]",
];

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|c| c.parse().ok())
            .unwrap_or(256),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        if let Ok(kb) = Kb::parse_bytes(&bytes, "fuzz.kb") {
            exercise(&kb, &["top", "x", "not(x)"]);
        }
    }

    #[test]
    fn kb_shaped_text_never_panics(parts in prop::collection::vec(prop::sample::select(PIECES), 0..60)) {
        let text = parts.concat();
        if let Ok(kb) = Kb::parse_bytes(text.as_bytes(), "fuzz.kb") {
            exercise(&kb, &["top", "a", "b", "p", "not(p)", "[a,b]"]);
        }
    }
}

#[test]
fn bad_bytes_have_a_position() {
    let e = Kb::parse_bytes(b"[class(top,none,[],[],[])\n,\xff]", "k.kb").unwrap_err();
    assert_eq!(e.pos, Some((2, 2)));
    assert_eq!(
        e.to_string(),
        "k.kb:2:2: error: invalid UTF-8 (byte 0xFF): the file must be UTF-8 text"
    );
    let e = Kb::parse_bytes(b"\xff\xfe[\0]\0", "k.kb").unwrap_err();
    assert!(e.message.contains("UTF-16"), "{e}");
    assert!(Kb::parse_bytes(b"\xef\xbb\xbf[class(top,none,[],[],[])].", "k.kb").is_ok());
}
