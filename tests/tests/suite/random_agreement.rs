//! Agreement on random programs (issue 5): the well-formed random
//! applications of `tests/gen/random_dm.rs` (compiled to Rust by
//! `tests/build.rs`, table `RANDOM_APPS`: random DMs, list walkers, two-list
//! walkers and recursive walkers of atoms, ints and lists by compound ids)
//! run on random scripts once on the
//! reference interpreter and once as generated Rust; the JSON reports
//! (status, error text, history, out_arg, globals) must be equal up to a
//! consistent renaming of variables, errors included.

use proptest::prelude::*;
use sitlog_compiler::ir::Ir;
use sitlog_compiler::run::{self, RunConfig};
use sitlog_runtime::machine::Options;
use sitlog_runtime::report;
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::Functions;
use sitlog_tests::compiled::canonical_vars;
use sitlog_tests::compiled::generated::RANDOM_APPS;
use sitlog_tests::random_dm;
use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;

/// The script's name, as error messages show it (the same on both sides).
const SCRIPT: &str = "script.txt";

fn report_json(text: String) -> serde_json::Value {
    serde_json::from_str(&text).unwrap_or(serde_json::Value::String(text))
}

/// Checks and lowers the random application at `dir`; panics with the
/// diagnostics if it has errors.
fn lower(dir: &Path) -> Ir {
    let (result, diags) = sitlog_compiler::check_path(dir).expect("random program is readable");
    match result {
        Ok(checked) => sitlog_compiler::ir::lower(&checked),
        Err(p) => {
            let text: Vec<String> = diags
                .iter()
                .filter(|d| d.is_error())
                .map(|d| sitlog_compiler::diag::render_short(d, &p.sources))
                .collect();
            panic!("{} does not check:\n{}", dir.display(), text.join("\n"));
        }
    }
}

thread_local! {
    /// The lowered programs, by index in `RANDOM_APPS` (lowered once per thread).
    static IRS: RefCell<Vec<Option<Rc<Ir>>>> = const { RefCell::new(Vec::new()) };
}

fn ir(index: usize) -> Rc<Ir> {
    IRS.with(|irs| {
        let mut irs = irs.borrow_mut();
        if irs.len() <= index {
            irs.resize(index + 1, None);
        }
        irs[index]
            .get_or_insert_with(|| Rc::new(lower(Path::new(RANDOM_APPS[index].1))))
            .clone()
    })
}

/// How a program is run: its main DM's in_arg and the machine's options.
#[derive(Clone, Debug)]
struct Run {
    in_arg: Option<&'static str>,
    keep_history: bool,
    max_depth: usize,
}

impl Default for Run {
    fn default() -> Run {
        Run {
            in_arg: None,
            keep_history: true,
            max_depth: Options::default().max_depth,
        }
    }
}

impl Run {
    fn options(&self) -> Options {
        Options {
            keep_history: self.keep_history,
            max_depth: self.max_depth,
            ..Options::default()
        }
    }
}

/// The reference interpreter's report of program `index` on `script`:
/// situations from their plans (`resolved`, what `sitlogc run` does) or
/// all instantiated from their templates.
fn interpreted(index: usize, script: &str, how: &Run, resolved: bool) -> serde_json::Value {
    let ir = ir(index);
    let mut perception = ScriptPerception::new(SCRIPT, script.to_owned());
    let mut actions = TextActions::new(std::io::sink(), ir.basic_actions.clone());
    let config = RunConfig {
        main: "main".to_owned(),
        in_arg: how.in_arg.map(str::to_owned),
        options: how.options(),
        functions: Functions::standard(),
    };
    let run = if resolved {
        run::run
    } else {
        run::run_unresolved
    };
    let (outcome, store) =
        run(&ir, config, &mut perception, &mut actions, None).expect("valid run config");
    report_json(report::outcome_json(&store, &outcome))
}

/// The generated code's report of program `index` on `script`.
fn compiled(index: usize, script: &str, how: &Run) -> serde_json::Value {
    let (_, _, run, functions) = RANDOM_APPS[index];
    let mut perception = ScriptPerception::new(SCRIPT, script.to_owned());
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let functions = functions().expect("standard functions");
    let (outcome, store) = run(
        "main",
        how.in_arg,
        how.options(),
        functions,
        &mut perception,
        &mut actions,
        None,
    )
    .expect("valid run config");
    report_json(report::outcome_json(&store, &outcome))
}

/// Runs both back ends, the interpreter with and without its plans; on
/// disagreement, the message names the program, the script, how it was run
/// and the reports.
fn agree(index: usize, words: &[&str], how: &Run) -> Result<serde_json::Value, String> {
    let script = random_dm::script(words);
    let templates = canonical_vars(&interpreted(index, &script, how, false));
    let interp = canonical_vars(&interpreted(index, &script, how, true));
    let generated = canonical_vars(&compiled(index, &script, how));
    if interp == generated && templates == interp {
        Ok(interp)
    } else {
        Err(format!(
            "random program {} ({}) disagrees ({how:?}) on the script\n{script}\ntemplates   {templates}\ninterpreter {interp}\ncompiled    {generated}",
            RANDOM_APPS[index].0, RANDOM_APPS[index].1
        ))
    }
}

/// Transitions in a report's history, nested ones included.
fn transitions(history: &serde_json::Value) -> usize {
    match history {
        serde_json::Value::Array(items) => items.iter().map(transitions).sum(),
        serde_json::Value::Object(_) => 1,
        _ => 0,
    }
}

/// A deterministic script of `len` terms from `inputs` (xorshift64*).
fn fixed_script(inputs: &[String], seed: u64, round: u64, len: usize) -> Vec<&str> {
    let mut x = (seed << 32 | round) ^ 0x2545_F491_4F6C_DD1D;
    (0..len)
        .map(|_| {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            let r = x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33;
            inputs[r as usize % inputs.len()].as_str()
        })
        .collect()
}

#[test]
fn every_random_program_is_compiled_and_checks_clean() {
    let seeds: Vec<u64> = RANDOM_APPS.iter().map(|a| a.0).collect();
    let expected: Vec<u64> = random_dm::seeds().collect();
    assert_eq!(
        seeds, expected,
        "tests/build.rs left programs out (see its warnings)"
    );
    let mut failures = Vec::new();
    let mut short = Vec::new();
    for (index, (seed, dir, _, _)) in RANDOM_APPS.iter().enumerate() {
        let dir = Path::new(dir);
        // What build.rs wrote is what the generator makes now.
        for (name, text) in random_dm::program(*seed) {
            let on_disk = std::fs::read_to_string(dir.join(&name)).unwrap();
            assert_eq!(on_disk, text, "{} is stale", dir.join(name).display());
        }
        // No errors, and no warnings but unreachable situations (W0213)
        // and finals never reached (W0214): the generator draws its jumps
        // at random.
        let (result, diags) = sitlog_compiler::check_path(dir).unwrap();
        let unexpected: Vec<_> = diags
            .iter()
            .filter(|d| d.is_error() || !["W0213", "W0214"].contains(&d.code))
            .collect();
        assert!(
            result.is_ok() && unexpected.is_empty(),
            "random program {seed} does not check clean: {unexpected:#?}"
        );
        // Some script drives it through a few transitions, and the two
        // back ends agree on every one of these scripts.
        let inputs = random_dm::inputs(*seed);
        for input in &inputs {
            assert!(random_dm::VOCABULARY.contains(&input.as_str()), "{input}");
        }
        let mut most = 0;
        for round in 0..40 {
            let script = fixed_script(&inputs, *seed, round, 40 - round as usize);
            let how = Run {
                in_arg: [None, Some("w(b)")][(round % 3 == 2) as usize],
                keep_history: round % 5 != 4,
                ..Run::default()
            };
            match agree(index, &script, &how) {
                Ok(report) if how.keep_history => most = most.max(transitions(&report["history"])),
                Ok(_) => {}
                Err(e) => failures.push(e),
            }
        }
        if most < 3 {
            short.push(format!("{seed} (at most {most})"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // The programs together make every construct the generator has (the
    // seeds are chosen for it: `random_dm::SEEDS`).
    let texts: Vec<String> = RANDOM_APPS
        .iter()
        .filter(|a| a.0 < random_dm::WALKER_SEED)
        .map(|a| {
            random_dm::program(a.0)
                .into_iter()
                .filter(|(name, _)| name.ends_with(".dm"))
                .map(|(_, text)| text + "\n")
                .collect()
        })
        .collect();
    assert_makes(
        CONSTRUCTS,
        &texts,
        "no random program of random_dm::SEEDS makes",
    );
    // The recursive walkers together make theirs (issue 37: atoms, lists
    // and compound ids).
    let rec: Vec<String> = RANDOM_APPS
        .iter()
        .filter(|a| a.0 >= random_dm::REC_SEED)
        .map(|a| {
            random_dm::program(a.0)
                .into_iter()
                .map(|(_, t)| t)
                .collect()
        })
        .collect();
    assert_eq!(rec.len() as u64, random_dm::REC_WALKERS);
    assert_makes(REC_CONSTRUCTS, &rec, "no recursive walker program makes");
    assert!(
        short.is_empty(),
        "random programs that never make 3 transitions: {}",
        short.join(", ")
    );
}

/// What the recursive walkers (`random_dm::REC_SEED..`) make, together.
const REC_CONSTRUCTS: &[(&str, Shows)] = &[
    (
        "a recursive compound id of a list pattern and an int",
        |t| t.contains("id ==> try([P|Rest], I), type ==> recursive"),
    ),
    ("a call with arguments, one an atom", |t| {
        t.contains("(P, T, tag)")
    }),
    ("a next id computed by `is`", |t| {
        t.contains("try(Rest, _J is I + 1)")
    }),
    ("a compound final of an element and an int", |t| {
        t.contains("id ==> found(_P, ")
    }),
    ("the limit read from the pipe", |t| {
        t.contains("in_arg ==> Lim")
    }),
    ("a final's out_arg into the pipe", |t| {
        t.contains("out_arg ==> I")
    }),
    ("a callee handing the pipe on", |t| {
        t.contains("in_arg ==> N, out_arg ==> N")
    }),
    ("a say of the element", |t| t.contains("say([at, P])")),
    ("a list of atoms", |t| {
        t.contains("v0([a") || t.contains("v1([a")
    }),
    ("a list of ints", |t| {
        t.contains("v0([0")
            || t.contains("v0([1")
            || t.contains("v0([2")
            || t.contains("v0([7")
            || t.contains("v0([9")
    }),
    ("a list of lists", |t| {
        t.contains("v0([[") || t.contains("v1([[")
    }),
];

/// Whether a program's DM text shows a construct.
type Shows = fn(&str) -> bool;

/// That some text of `texts` shows each construct of `constructs`, else
/// `what` and the missing ones.
fn assert_makes(constructs: &[(&str, Shows)], texts: &[String], what: &str) {
    let missing: Vec<&str> = constructs
        .iter()
        .filter(|(_, made)| !texts.iter().any(|t| made(t)))
        .map(|(what, _)| *what)
        .collect();
    assert!(missing.is_empty(), "{what}: {}", missing.join("; "));
}

/// Every construct of `tests/gen/random_dm.rs`'s random programs, with how
/// a program's DM text shows it.
const CONSTRUCTS: &[(&str, Shows)] = &[
    ("a third DM", |t| t.contains("diag_mod(sub2")),
    ("a sub without parameters", |t| {
        t.contains("diag_mod(sub1,\n") || t.contains("diag_mod(sub2,\n")
    }),
    ("a sub(Result)", |t| t.contains("(Hr),\n")),
    ("a sub(Param, Result)", |t| t.contains("(Hp, Hr),\n")),
    ("a list walk tick([H|T])", |t| {
        t.contains("([H") && t.contains("|T")
    }),
    ("a countdown tick(0)/tick(N)", |t| t.contains("(0),\n")),
    ("a speech situation ask(K)", |t| t.contains("id ==> ask")),
    ("a final with a parameter", |t| t.contains("id ==> got")),
    ("an in_arg", |t| t.contains("in_arg ==>")),
    ("an in_arg pattern w(In)", |t| t.contains("in_arg ==> w(In")),
    ("an out_arg", |t| t.contains("out_arg ==>")),
    ("a final's diag_mod", |t| t.contains("diag_mod ==>")),
    ("a diag_mod that does not unify (E9)", |t| {
        t.contains("(zz, ")
    }),
    ("a diag_mod value zz", |t| t.contains("(zz)")),
    ("a recursive situation", |t| t.contains("embedded_dm ==>")),
    ("a conditional", |t| t.contains(" -> ")),
    ("prog", |t| t.contains("prog ==>")),
    ("said(X)", |t| t.contains("said(")),
    ("num(N)", |t| t.contains("num(")),
    ("a list expected", |t| t.contains("[a, ")),
    ("append", |t| t.contains("append(")),
    ("member", |t| t.contains("member(")),
    ("is", |t| t.contains(" is ")),
    ("the global g_log", |t| t.contains("g_log")),
    ("inc of a non-number (E7)", |t| {
        t.contains("inc(v, _)") || t.contains("inc(g_log, _)")
    }),
    ("a next situation named by the input (E8)", |t| {
        t.lines().any(|l| {
            let l = l.trim_end_matches(',');
            l.split_once("said(")
                .and_then(|(_, rest)| rest.split_once(") : "))
                .is_some_and(|(x, rest)| rest.ends_with(&format!("=> {x}")))
        })
    }),
];

/// A program's index in `RANDOM_APPS` and a script of 0–39 terms drawn from
/// its inputs (terms its arcs expect, and terms that match nothing).
fn program_and_script() -> impl Strategy<Value = (usize, Vec<String>)> {
    (0..RANDOM_APPS.len()).prop_flat_map(|index| {
        let inputs = random_dm::inputs(RANDOM_APPS[index].0);
        (
            Just(index),
            prop::collection::vec(prop::sample::select(inputs), 0..40),
        )
    })
}

/// Mostly the defaults; sometimes an in_arg (`w(b)` meets the `w(In)`
/// patterns), no history (`--history none`) or a shallow DM stack limit.
fn how() -> impl Strategy<Value = Run> {
    (
        prop::sample::select(vec![
            None,
            None,
            None,
            Some("a"),
            Some("num(1)"),
            Some("w(b)"),
        ]),
        prop::bool::weighted(0.8),
        prop_oneof![8 => Just(Options::default().max_depth), 2 => 1..4usize],
    )
        .prop_map(|(in_arg, keep_history, max_depth)| Run {
            in_arg,
            keep_history,
            max_depth,
        })
}

fn config() -> ProptestConfig {
    // PROPTEST_CASES (CI: 64) overrides the default of 256.
    ProptestConfig {
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_programs_agree_on_random_scripts(
        (index, words) in program_and_script(),
        how in how(),
    ) {
        let words: Vec<&str> = words.iter().map(String::as_str).collect();
        if let Err(e) = agree(index, &words, &how) {
            prop_assert!(false, "{}", e);
        }
    }
}

/// The MIR's type inference (`mir::ty`, phase 1 of the typed MIR) over
/// every random program: it ends without a panic and types every register
/// of every plan.
#[test]
fn mir_types_of_every_random_program() {
    for index in 0..RANDOM_APPS.len() {
        let ir = ir(index);
        let mir = sitlog_compiler::mir::lower(&ir);
        let t = sitlog_compiler::mir::ty::infer(&ir, &mir);
        for (d, plans) in mir.dms.iter().enumerate() {
            for (s, p) in plans.iter().enumerate() {
                let regs = t.dms[d].sits[s].as_ref().map(|x| x.regs.len());
                assert_eq!(regs, p.as_ref().map(|p| p.regs), "program {index}");
            }
        }
        let (typed, regs, clean, sits) = t.counts();
        assert!(typed <= regs && clean <= sits, "program {index}");
    }
}
