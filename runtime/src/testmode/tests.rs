//! Tests of test mode's script reading: input limits, plain atoms read
//! as our reader reads them, and scripts streamed term by term; the text
//! effector says it ignores only what it shows nothing of.

use super::*;

#[cfg(test)]
mod limit_tests {
    use super::*;

    fn first(p: &mut dyn Perception) -> Result<Perceived, String> {
        let mut store = Store::new();
        let ty = Term::atom(Atom::intern("listening"));
        p.perceive(&mut store, ty, &[])
    }

    #[test]
    fn scripts_obey_the_input_limits_with_positions() {
        let limits = InputLimits {
            max_bytes: 20,
            max_depth: 5,
        };
        let script =
            |text: &str| ScriptPerception::new("s.txt", text.to_owned()).with_limits(limits);
        assert!(matches!(
            first(&mut script("% c\nf(a).\n")),
            Ok(Perceived::Input(_))
        ));
        let e = first(&mut script("ok.\n")).map(|_| ());
        assert!(e.is_ok());
        let long = format!("\n  [{}].\n", "1,".repeat(20) + "1");
        let e = first(&mut script(&long)).unwrap_err();
        assert!(
            e.starts_with("s.txt:2:3: the input is longer than 20 bytes"),
            "{e}"
        );
        assert!(e.contains("--max-input-bytes"), "{e}");
        let e = first(&mut script("f(f(f(f(f(f(a)))))).")).unwrap_err();
        assert!(e.contains("nested more than 5 levels deep"), "{e}");
        assert!(e.contains("--max-input-depth"), "{e}");
        // Exactly at the limit is fine.
        assert!(first(&mut script("f(f(f(f(a)))).")).is_ok());
        let e = ScriptPerception::from_bytes("s.txt", b"a.\n\xc3(".to_vec())
            .err()
            .unwrap();
        assert!(e.contains("s.txt:2:1"), "{e}");
    }

    #[test]
    fn the_prompt_names_the_dm_the_situation_and_the_expectations() {
        let mut store = Store::new();
        let ty = Term::atom(Atom::intern("listening"));
        let (go, _) = store.parse("said(go)").unwrap();
        let (any, _) = store.parse("said(X)").unwrap();
        let (dm, _) = store.parse("'find it'(cup, L)").unwrap();
        let (sit, _) = store.parse("ask(2)").unwrap();
        let at = waiting_text(&store, dm, sit);
        assert_eq!(at, ("'find it'".to_owned(), "ask(2)".to_owned()));
        assert_eq!(
            prompt_header(&store, Some(&at), ty, &[go, any]),
            "DM 'find it', situation ask(2) (listening) expects: said(go) | said(_G0)"
        );
        assert_eq!(
            prompt_header(&store, None, ty, &[go]),
            "[listening] expectations: said(go)"
        );
    }

    #[test]
    fn typed_input_obeys_the_limits_and_names_bad_bytes() {
        let limits = InputLimits {
            max_bytes: 10,
            max_depth: 3,
        };
        let mut p = PromptPerception::new(&b"[1,2,3,4,5,6,7].\n"[..]).with_limits(limits);
        let e = first(&mut p).unwrap_err();
        assert!(e.contains("longer than 10 bytes"), "{e}");
        let mut p = PromptPerception::new(&b"f(g(h(i(j)))).\n"[..]).with_limits(InputLimits {
            max_bytes: 100,
            max_depth: 3,
        });
        assert!(first(&mut p).unwrap_err().contains("nested more than 3"));
        let mut p = PromptPerception::new(&b"ok.\nab \xff.\n"[..]).with_limits(limits);
        assert!(first(&mut p).is_ok());
        let e = first(&mut p).unwrap_err();
        assert!(e.starts_with("standard input:2:4:"), "{e}");
    }

    #[test]
    fn endless_typed_input_is_refused_at_the_limit() {
        // `< /dev/zero`: one line that never ends
        let limits = InputLimits {
            max_bytes: 4096,
            max_depth: 10,
        };
        let zeros = std::io::BufReader::new(std::io::repeat(0));
        let mut p = PromptPerception::new(zeros).with_limits(limits);
        let e = first(&mut p).unwrap_err();
        assert!(
            e.starts_with("standard input:1:1: the input is longer than 4096 bytes"),
            "{e}"
        );
        // a term over many lines, each under the limit, together over it
        let many = "[\n".to_owned() + &"a,\n".repeat(3000) + "b].\n";
        let mut p = PromptPerception::new(many.as_bytes()).with_limits(limits);
        let e = first(&mut p).unwrap_err();
        assert!(e.contains("longer than 4096 bytes"), "{e}");
    }

    #[test]
    fn a_term_over_many_lines_is_read_once() {
        let lines = 5_000;
        let text = "[\n".to_owned() + &"a,\n".repeat(lines) + "b].\nok.\n";
        let mut store = Store::new();
        let ty = Term::atom(Atom::intern("speech"));
        let mut p = PromptPerception::new(text.as_bytes());
        let Ok(Perceived::Input(t)) = p.perceive(&mut store, ty, &[]) else {
            panic!("no input");
        };
        assert_eq!(store.list_to_vec(t).map(|v| v.len()), Some(lines + 1));
        let Ok(Perceived::Input(t)) = p.perceive(&mut store, ty, &[]) else {
            panic!("no second input");
        };
        assert_eq!(store.writeq(t), "ok");
        assert!(matches!(
            p.perceive(&mut store, ty, &[]),
            Ok(Perceived::EndOfInput)
        ));
    }

    #[test]
    fn the_end_scan_finds_end_tokens_outside_quotes_and_comments() {
        let ends = |lines: &[&str]| {
            let mut s = prompt::EndScan::default();
            lines.iter().map(|l| s.feed(l)).collect::<Vec<bool>>()
        };
        assert_eq!(ends(&["f(a).\n"]), [true]);
        assert_eq!(ends(&["f(a)."]), [true]);
        assert_eq!(ends(&["f(a).% c\n"]), [true]);
        assert_eq!(ends(&["[1.5,\n", "2]\n"]), [false, false]);
        assert_eq!(ends(&["X =.. Y\n"]), [false]);
        assert_eq!(ends(&["'a. \n", "b'.\n"]), [false, true]);
        assert_eq!(ends(&["\"a. \\\" b. \n", "\".\n"]), [false, true]);
        assert_eq!(ends(&["/* a. \n", "b. */ c.\n"]), [false, true]);
        assert_eq!(ends(&["% a. \n", "b.\n"]), [false, true]);
        assert_eq!(ends(&["X = 0'a, Y = 0''', Z = 0'\\'.\n"]), [true]);
        assert_eq!(ends(&["X = 0'. \n"]), [false]);
        assert_eq!(ends(&["X = 16'FF.\n"]), [true]);
    }
}

#[cfg(test)]
mod plain_atom_tests {
    use super::*;

    /// Every input of `script`, read with and without the plain-atom path:
    /// the same terms, errors and positions.
    fn same_both_ways(script: &str) {
        let ty = Term::atom(Atom::intern("speech"));
        let mut fast = ScriptPerception::new("s", script.to_owned());
        let mut slow = ScriptPerception::new("s", script.to_owned());
        slow.atoms_fast = false;
        let (mut a, mut b) = (Store::new(), Store::new());
        for _ in 0..20 {
            let x = fast.perceive(&mut a, ty, &[]);
            let y = slow.perceive(&mut b, ty, &[]);
            let show = |s: &Store, r: &Result<Perceived, String>| match r {
                Ok(Perceived::Input(t)) => format!("input {}", s.writeq(*t)),
                other => format!("{other:?}"),
            };
            assert_eq!(show(&a, &x), show(&b, &y), "in {script:?}");
            assert_eq!(fast.pos, slow.pos, "position in {script:?}");
            if !matches!(y, Ok(Perceived::Input(_))) {
                break;
            }
        }
    }

    #[test]
    fn plain_atoms_read_as_the_term_reader_reads_them() {
        for script in [
            "tick.\nstop.\n",
            "tick.",
            "  tick.\n\n  tock_2.\tx.\r\nyY.",
            "tick",
            "tick .\n",
            "tick.%c\nstop.\n",
            "'tick'.\n",
            "tick(a).\n",
            "abc.def.\n",
            "is.\n",
            "mod.\nrem.\n",
            "dynamic.\n",
            "a.b.\n",
            "é.\n",
            "Tick.\n",
            "_x.\n",
            "% comment\ntick.\n",
            "/* c */ tick.\n",
            "tick..\n",
            "tick.\u{a0}stop.\n",
            "",
            "   \n",
            // Words read again (`RecentAtoms`): more than it keeps, an
            // operator twice, words of 8 and 9 bytes.
            "no.\nno.\nyes.\nno.\nyes.\n",
            "a.b.\nc.\nd.\ne.\na.\nf.\nb.\ne.\n",
            "is.\nis.\n",
            "abcdefgh.\nabcdefgh.\nabcdefghi.\nabcdefghi.\nabcdefgh.\n",
            "ab.\nabc.\nab.\nabc.\n",
        ] {
            same_both_ways(script);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// Scripts made of atom-like pieces, dots, layout, comments,
        /// quotes, brackets and operators read the same both ways.
        #[test]
        fn scripts_read_the_same_both_ways(
            pieces in proptest::collection::vec(
                proptest::sample::select(vec![
                    "tick", "a", "zZ_9", "is", "mod", "dynamic", "X", "_", "'q'", "é",
                    ".", ".", ". ", ".\n", "\n", " ", "\t", "%c\n", "/*c*/", "(", ")",
                    "[]", ",", "+", "-", "1", "0.5", "\u{a0}",
                ]),
                0..12,
            )
        ) {
            same_both_ways(&pieces.concat());
        }
    }

    #[test]
    fn plain_atoms_keep_the_byte_limit() {
        let long = format!("{}.\n", "a".repeat(100));
        let limits = InputLimits {
            max_bytes: 50,
            ..InputLimits::default()
        };
        let ty = Term::atom(Atom::intern("speech"));
        let mut fast = ScriptPerception::new("s", long.clone()).with_limits(limits);
        let mut slow = ScriptPerception::new("s", long).with_limits(limits);
        slow.atoms_fast = false;
        let (mut a, mut b) = (Store::new(), Store::new());
        assert_eq!(
            fast.perceive(&mut a, ty, &[]),
            slow.perceive(&mut b, ty, &[])
        );
    }
}

#[cfg(test)]
mod stream_tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Arc;

    fn inputs(mut p: ScriptPerception) -> Vec<String> {
        let ty = Term::atom(Atom::intern("speech"));
        let mut store = Store::new();
        let mut out = Vec::new();
        for _ in 0..30 {
            let r = p.perceive(&mut store, ty, &[]);
            let done = !matches!(r, Ok(Perceived::Input(_)));
            out.push(match r {
                Ok(Perceived::Input(t)) => format!("input {}", store.writeq(t)),
                other => format!("{other:?}"),
            });
            if done {
                break;
            }
        }
        out
    }

    /// A pipe giving its bytes a few at a time.
    fn piped(text: &str) -> Box<dyn BufRead + Send> {
        Box::new(std::io::BufReader::with_capacity(
            3,
            std::io::Cursor::new(text.as_bytes().to_vec()),
        ))
    }

    /// The same inputs, in order, and the same end: the end of input, or a
    /// syntax error at the same step (the whole script's reader may name a
    /// token error further on; the streamed one names the first it meets).
    fn same_streamed(script: &str, limits: InputLimits) {
        let whole = ScriptPerception::new("s", script.to_owned()).with_limits(limits);
        let streamed = ScriptPerception::from_reader("s", piped(script)).with_limits(limits);
        let (mut a, mut b) = (inputs(whole), inputs(streamed));
        let error = |v: &Vec<String>| v.last().is_some_and(|l| l.contains("syntax error"));
        if error(&a) {
            // the whole script's reader meets a token error further on at
            // the first input after the last good one; the streamed reader
            // takes the good inputs before it, then stops at an error too
            assert!(error(&b), "in {script:?}: {b:?}");
            a.pop();
            b.pop();
            assert!(b.starts_with(&a), "in {script:?}: {a:?} {b:?}");
        } else {
            assert_eq!(a, b, "in {script:?}");
        }
    }

    #[test]
    fn a_streamed_script_reads_as_the_whole_one() {
        let limits = InputLimits::default();
        for script in [
            "tick.\nstop.\n",
            "f(a,\n  b).\ng.\n",
            "'multi\nline'.\nx.\n",
            "/* a\ncomment */ x.\n% c\ny.",
            "f(a.\n",
            "f(\n",
            "\n\n\n",
            "x.\ny \u{7f}.\n",
            "1.\n5.\n",
            "[1,\n2,\n3].\n",
        ] {
            same_streamed(script, limits);
        }
        let small = InputLimits {
            max_bytes: 20,
            max_depth: 4,
        };
        for script in [
            "\n  [1,1,1,1,1,1,1,1,1,1,1,1,1].\n",
            "[1,\n1,\n1,\n1,\n1,\n1,\n1,\n1,\n1,\n1,\n1].\nok.\n",
            "f(f(f(f(f(a))))).\n",
            "okay.\nfine.\n",
        ] {
            same_streamed(script, small);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]
        #[test]
        fn streamed_scripts_read_as_whole_ones(
            pieces in proptest::collection::vec(
                proptest::sample::select(vec![
                    "tick", "a", "X", "'q", "'", "é", ".", ". ", ".\n", "\n", " ",
                    "%c\n", "/*", "*/", "(", ")", "[", "]", ",", "1", "0.5", "\"s",
                ]),
                0..16,
            )
        ) {
            same_streamed(&pieces.concat(), InputLimits::default());
        }
    }

    /// Text that is not UTF-8 is an error at its line in the whole script.
    #[test]
    fn bad_bytes_are_named_at_their_line() {
        let bytes = b"a.\nb.\nc \xff.\n".to_vec();
        let p = ScriptPerception::from_reader(
            "s.txt",
            Box::new(std::io::BufReader::with_capacity(
                2,
                std::io::Cursor::new(bytes),
            )),
        );
        let got = inputs(p);
        assert_eq!(got[0], "input a");
        assert!(got.last().unwrap().contains("s.txt:3:3"), "{got:?}");
    }

    /// An endless source: only what the inputs taken need is read.
    #[test]
    fn only_what_is_consumed_is_read() {
        struct Endless(Arc<AtomicUsize>);
        impl std::io::Read for Endless {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let line = b"quit.\n";
                let n = buf.len().min(line.len());
                buf[..n].copy_from_slice(&line[..n]);
                self.0.fetch_add(n, Ordering::Relaxed);
                Ok(n)
            }
        }
        let count = Arc::new(AtomicUsize::new(0));
        let mut p = ScriptPerception::from_reader(
            "stdin",
            Box::new(std::io::BufReader::new(Endless(count.clone()))),
        );
        let ty = Term::atom(Atom::intern("speech"));
        let mut store = Store::new();
        for _ in 0..3 {
            assert!(matches!(
                p.perceive(&mut store, ty, &[]),
                Ok(Perceived::Input(_))
            ));
        }
        assert!(
            count.load(Ordering::Relaxed) < 64 * 1024,
            "{}",
            count.load(Ordering::Relaxed)
        );
        // a long run keeps its memory: consumed lines are dropped
        for _ in 0..200_000 {
            assert!(matches!(
                p.perceive(&mut store, ty, &[]),
                Ok(Perceived::Input(_))
            ));
        }
        assert!(p.text.len() < 1 << 18, "{}", p.text.len());
    }
}

#[cfg(test)]
mod text_actions_tests {
    use super::*;

    /// `TextActions::ignores` says yes only of actions `perform` shows
    /// nothing of, whatever their arguments.
    #[test]
    fn ignored_actions_show_nothing() {
        let mut store = Store::new();
        let declared = vec![Atom::intern("grasp")];
        let v = store.new_var();
        let a = Term::atom(Atom::intern("x"));
        for name in ["say", "screen", "grasp", "note", "navigate"] {
            let f = Atom::intern(name);
            for args in [vec![], vec![a], vec![v], vec![a, v]] {
                let action = store.compound(f, &args);
                let mut out = Vec::new();
                let mut actions = TextActions::new(&mut out, declared.clone());
                let ignored = actions.ignores(ActionShape::Named(f, args.len()));
                assert!(actions.perform(&mut store, action).is_ok());
                let shown = !out.is_empty();
                assert_eq!(ignored, !shown, "{name}/{}", args.len());
            }
        }
    }
}

/// `RecentAtoms` keys a word by its packed text, loaded in one where the
/// text has eight bytes from its start, copied near the end: the same
/// atom either way, words that are prefixes of one another kept apart.
#[test]
fn recent_atoms_key_words_by_their_text() {
    let mut recent = super::RecentAtoms::default();
    let text = "no. no_. nothing8. no. a. ab.";
    let words: Vec<(usize, usize)> = text
        .match_indices(|c: char| c.is_ascii_alphanumeric() || c == '_')
        .fold(Vec::new(), |mut v: Vec<(usize, usize)>, (i, _)| {
            match v.last_mut() {
                Some((_, end)) if *end == i => *end = i + 1,
                _ => v.push((i, i + 1)),
            }
            v
        });
    for _ in 0..2 {
        for &(start, end) in &words {
            assert_eq!(
                recent.atom(text, start, end),
                Some(Atom::intern(&text[start..end])),
                "{}",
                &text[start..end]
            );
        }
    }
}

/// `TextActions::perform_filled` writes the line `perform` writes of the
/// term filled (a pattern's holes atoms or numbers), byte for byte.
#[test]
fn filled_actions_show_the_filled_terms_line() {
    let patterns = [
        "say([checking,'$hole'(0)])",
        "say(['$hole'(0),is,at,'$hole'(1)])",
        "say(['$hole'(0),pause,'$hole'(1),f('$hole'(0))])",
        "say(['$hole'(0)|'$hole'(1)])",
        "say(hello('$hole'(0)))",
        "screen(['$hole'(0),'$hole'(1)])",
        "point(left,'$hole'(1))",
        "grasp(['$hole'(0)],'$hole'(1),'A b')",
        "note('$hole'(0))",
    ];
    let hole_sets: [&[&str]; 4] = [
        &["p3", "7"],
        &["'Living room'", "-2.5"],
        &["[]", "pause"],
        &["'$hole'", "99999999999999999999"],
    ];
    for text in patterns {
        for hs in hole_sets {
            let mut store = Store::new();
            let [k] = crate::machine::read_consts(&mut store, &[text]);
            let holes: Vec<Term> = hs.iter().map(|h| store.parse(h).unwrap().0).collect();
            let declared = vec![Atom::intern("grasp"), Atom::intern("point")];
            let mut filled_out = Vec::new();
            let mut actions = TextActions::new(&mut filled_out, declared.clone());
            let done = actions.perform_filled(&mut store, k, &holes);
            assert!(matches!(done, Some(Ok(()))), "{text}");
            let refs: Vec<&dyn crate::machine::AsTerm> = holes
                .iter()
                .map(|t| t as &dyn crate::machine::AsTerm)
                .collect();
            let t = crate::machine::fill(&mut store, k, &refs);
            let mut out = Vec::new();
            TextActions::new(&mut out, declared)
                .perform(&mut store, t)
                .unwrap();
            assert_eq!(
                String::from_utf8(filled_out).unwrap(),
                String::from_utf8(out).unwrap(),
                "{text} {hs:?}"
            );
        }
    }
}

/// A `say` pattern's line planned once (`said`): the plan's line, the
/// walk's and `perform`'s of the term filled are the same, byte for byte,
/// the first time and the next; a pattern with a hole below a compound
/// item or as a tail, or a hole whose value is `pause`, written by the
/// walk.
#[test]
fn planned_say_lines_are_the_filled_terms_lines() {
    let patterns = [
        ("say([checking,'$hole'(0)])", true),
        ("say('$hole'(0))", true),
        ("say(['$hole'(0)])", true),
        ("say(['$hole'(0),is,at,'$hole'(1)])", true),
        ("say(['$hole'(1),'$hole'(0)])", true),
        ("say([pause,'$hole'(0)])", true),
        ("say(['$hole'(0),pause])", true),
        ("say(['It''s','$hole'(0),pause,'Living room',[a,'B c'],3,-2,1.5,f(x),'$hole'(1),pause])", true),
        ("say(['$hole'(0),pause,'$hole'(1),f('$hole'(0))])", false),
        ("say(['$hole'(0)|'$hole'(1)])", false),
        ("say([a,'$hole'(0)|b])", false),
        ("say(hello('$hole'(0)))", false),
        ("say(['$hole'(5)])", true),
    ];
    let hole_sets: [&[&str]; 6] = [
        &["p3", "7"],
        &["'Living room'", "-2.5"],
        &["[]", "pause"],
        &["pause", "x"],
        &["'$hole'", "99999999999999999999"],
        &["-7", "'a\\nb'"],
    ];
    for (text, planned) in patterns {
        let mut store = Store::new();
        let [k] = crate::machine::read_consts(&mut store, &[text]);
        store.freeze();
        let mut filled_out = Vec::new();
        let mut actions = TextActions::new(&mut filled_out, Vec::new());
        let mut expected = String::new();
        for _ in 0..2 {
            for hs in hole_sets {
                let holes: Vec<Term> = hs.iter().map(|h| store.parse(h).unwrap().0).collect();
                let done = actions.perform_filled(&mut store, k, &holes);
                assert!(matches!(done, Some(Ok(()))), "{text}");
                let refs: Vec<&dyn crate::machine::AsTerm> = holes
                    .iter()
                    .map(|t| t as &dyn crate::machine::AsTerm)
                    .collect();
                let t = crate::machine::fill(&mut store, k, &refs);
                let mut out = Vec::new();
                TextActions::new(&mut out, Vec::new())
                    .perform(&mut store, t)
                    .unwrap();
                expected.push_str(&String::from_utf8(out).unwrap());
            }
        }
        assert_eq!(actions.plans.planned(), usize::from(planned), "{text}");
        drop(actions);
        assert_eq!(String::from_utf8(filled_out).unwrap(), expected, "{text}");
    }
}

/// A plan is of one store: the same place in another store's frozen
/// region holds another pattern.
#[test]
fn planned_say_lines_are_of_one_store() {
    let mut out = Vec::new();
    let mut actions = TextActions::new(&mut out, Vec::new());
    for text in ["say([one,'$hole'(0)])", "say([two,'$hole'(0),three])"] {
        let mut store = Store::new();
        let [k] = crate::machine::read_consts(&mut store, &[text]);
        store.freeze();
        let mut clone = store.clone();
        for s in [&mut store, &mut clone] {
            let done = actions.perform_filled(s, k, &[Term::int(1)]);
            assert!(matches!(done, Some(Ok(()))), "{text}");
        }
    }
    drop(actions);
    assert_eq!(
        String::from_utf8(out).unwrap(),
        "Golem says: one 1\nGolem says: one 1\nGolem says: two 1 three.\nGolem says: two 1 three.\n"
    );
}
