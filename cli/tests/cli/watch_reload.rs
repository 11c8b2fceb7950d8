//! Hot reload in process (issue 21): a [`Watched`] program is offered a new
//! IR while the run waits for input, as the watcher thread would offer it,
//! with embedded DMs on the stack and situations renumbered.

use sitlog_cli::watch::{Messages, ReloadAware, Watched};
use sitlog_compiler::ir::{lower, Ir};
use sitlog_runtime::machine::{Options, Perceived, Perception};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{Functions, Store, Term};
use std::sync::{Arc, Mutex};

fn ir_of(name: &str, files: &[(&str, &str)]) -> Ir {
    let dir =
        crate::support::temp_root().join(format!("sitlog-watch-ir-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    let (checked, diags) = sitlog_cli::output::check_app(&dir, Default::default()).unwrap();
    let checked = checked.unwrap_or_else(|_| panic!("{diags:?}"));
    lower(&checked)
}

const MAIN: &str = "diag_mod(main, [
  [id ==> is, type ==> recursive, embedded_dm ==> inner,
   arcs ==> [done : say(back) => fs]],
  [id ==> fs, type ==> final]
], [n ==> 1]).
";

const INNER: &str = "diag_mod(inner, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : say(one) => ask, said(stop) : say(bye) => done]],
  [id ==> done, type ==> final]
], []).
";

/// Offers `next` to the program the first time it is asked to perceive
/// (the run then waits in `inner`), then reads the script.
struct OfferOnce<'a> {
    watched: &'a Watched,
    next: Option<Ir>,
    inner: ReloadAware,
}

impl Perception for OfferOnce<'_> {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        if let Some(ir) = self.next.take() {
            self.watched.offer(ir, "inner.dm");
        }
        self.inner.perceive(store, ty, expectations)
    }
}

fn run(first: Ir, next: Ir, script: &str) -> (String, String, String) {
    let messages = Arc::new(Mutex::new(Vec::<u8>::new()));
    let sink: Messages = Arc::new(Mutex::new(Box::new(SharedVec(messages.clone()))));
    let watched = Watched::new(first, sink);
    let script = ScriptPerception::new("s.txt", script.to_owned());
    let mut perception = OfferOnce {
        watched: &watched,
        next: Some(next),
        inner: ReloadAware::new(Box::new(script), watched.ready_flag()),
    };
    let said = Arc::new(Mutex::new(Vec::<u8>::new()));
    let mut actions = TextActions::new(SharedVec(said.clone()), Vec::new());
    let (outcome, mut store) = sitlog_runtime::app::run(
        &watched,
        "main",
        None,
        Options::default(),
        Functions::standard(),
        &mut perception,
        &mut actions,
        None,
    )
    .unwrap();
    let report = sitlog_runtime::report::outcome_text(&mut store, &outcome);
    let text = |v: &Arc<Mutex<Vec<u8>>>| String::from_utf8_lossy(&v.lock().unwrap()).into_owned();
    let result = match &outcome.result {
        Ok(()) => String::new(),
        Err(e) => e.to_string(),
    };
    (format!("{report}{result}"), text(&said), text(&messages))
}

struct SharedVec(Arc<Mutex<Vec<u8>>>);

impl std::io::Write for SharedVec {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn an_embedded_dm_reloads_while_its_caller_waits() {
    let first = ir_of("first", &[("main.dm", MAIN), ("inner.dm", INNER)]);
    // The new program: the inner action changes, and main's recursive
    // situation moves (a situation before it), so its number changes.
    let main2 = MAIN.replace(
        "diag_mod(main, [\n",
        "diag_mod(main, [\n  [id ==> unused, type ==> final],\n",
    );
    let next = ir_of(
        "next",
        &[
            ("main.dm", &main2),
            ("inner.dm", &INNER.replace("say(one)", "say(two)")),
        ],
    );
    let (report, said, messages) = run(first, next, "go.\ngo.\nstop.\n");
    assert!(
        messages.contains("reloaded (inner.dm): the run goes on in the new program at DM `inner`, situation `ask`"),
        "{messages}"
    );
    // The input read while the new program waited is the new program's.
    assert_eq!(
        said,
        "Golem says: two\nGolem says: two\nGolem says: bye\nGolem says: back\n"
    );
    assert!(report.contains("Out Global Vars: []"), "{report}");
    assert!(
        report.contains("[\n  inner:(ask,said(go):say(two))\n  inner:(ask,said(go):say(two))\n  inner:(ask,said(stop):say(bye))\n  inner:(done,empty:empty)\n]\nmain:((is),done:say(back))\nmain:(fs,empty:empty)\n"),
        "{report}"
    );
}

#[test]
fn a_caller_whose_situation_is_gone_keeps_its_instance() {
    let first = ir_of("first2", &[("main.dm", MAIN), ("inner.dm", INNER)]);
    // `main` is now another DM: the waiting situation `is` is not in it.
    let next = ir_of(
        "next2",
        &[
            ("main.dm", &MAIN.replace("diag_mod(main,", "diag_mod(main2,")),
            ("inner.dm", INNER),
            (
                "start.dm",
                "diag_mod(main, [[id ==> s, type ==> recursive, embedded_dm ==> main2, arcs ==> [fs : empty => f]], [id ==> f, type ==> final]], []).\n",
            ),
        ],
    );
    let (report, said, messages) = run(first, next, "go.\nstop.\n");
    assert!(messages.contains("reloaded"), "{messages}");
    // The exit arc of the instance `is` was entered with is taken; its next
    // situation `fs` is not in the new `main`: a plain run-time error.
    assert!(said.ends_with("Golem says: back\n"), "{said}");
    assert!(report.contains("main:((is),done:say(back))"), "{report}");
    assert!(
        report.contains("there is no situation `fs` in this DM"),
        "{report}"
    );
}

#[test]
fn a_dm_on_the_stack_removed_stops_the_run() {
    let first = ir_of("first3", &[("main.dm", MAIN), ("inner.dm", INNER)]);
    let next = ir_of(
        "next3",
        &[(
            "main.dm",
            "diag_mod(main, [[id ==> is, type ==> final]], []).\n",
        )],
    );
    let (report, said, _) = run(first, next, "go.\n");
    assert_eq!(said, "");
    assert!(
        report.contains(
            "DM `inner`, on the DM stack (called as `inner`), is no longer in the program"
        ),
        "{report}"
    );
}
