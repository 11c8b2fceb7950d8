//! Arbitrary bytes as a KB file; a KB that loads is asked every query
//! service and given every update (each on a copy of the loaded KB), with
//! arguments drawn from its own names. Never a panic. A KB after an update
//! must save to text that loads: checked for one of the updates that
//! succeed (chosen by the input's length) and for the KB that all of them,
//! applied one after another, leave; re-reading the KB after each of the 29
//! updates made this target ten times slower (issue 31).
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_kb::{Kb, SERVICES, UPDATES};

fn saves_and_loads(kb: &Kb) {
    Kb::parse(&kb.to_text(), "again").expect("a KB after an update saves to text that loads");
}

fuzz_target!(|data: &[u8]| {
    let Ok(kb) = Kb::parse_bytes(data, "fuzz.kb") else {
        return;
    };
    // Names to use as arguments: some of the KB's own, and a few others.
    let text = kb.to_text();
    let mut names: Vec<String> = vec!["top".into(), "x".into(), "not(x)".into(), "[a,b]".into()];
    for part in text.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
        if !part.is_empty()
            && part.chars().next().is_some_and(|c| c.is_ascii_lowercase())
            && names.len() < 12
        {
            if !names.iter().any(|n| n == part) {
                names.push(part.to_owned());
            }
        }
    }
    for (k, s) in SERVICES.iter().enumerate() {
        let mut args: Vec<String> = (0..s.arity - 1)
            .map(|i| names[(k + i) % names.len()].clone())
            .collect();
        args.push("Answer".into());
        let _ = kb.query(&format!("{}({})", s.name, args.join(",")));
    }
    let mut updated = Vec::new();
    let mut all = kb.clone();
    let mut all_changed = false;
    for (k, u) in UPDATES.iter().enumerate() {
        let args: Vec<String> = (0..u.arity)
            .map(|i| names[(k + 2 * i) % names.len()].clone())
            .collect();
        let text = format!("{}({})", u.name, args.join(","));
        if let Ok(clause) = sitlog_syntax::read_term(&text) {
            let mut copy = kb.clone();
            if copy.update(&clause).is_ok() {
                updated.push(copy);
            }
            all_changed |= all.update(&clause).is_ok();
        }
    }
    if !updated.is_empty() {
        saves_and_loads(&updated[data.len() % updated.len()]);
    }
    if all_changed {
        saves_and_loads(&all);
    }
});
