//! Arbitrary bytes as a KB file; a KB that loads is asked every query
//! service and given every update (on a copy), with arguments drawn from
//! its own names. Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_kb::{Kb, SERVICES, UPDATES};

fuzz_target!(|data: &[u8]| {
    let Ok(kb) = Kb::parse_bytes(data, "fuzz.kb") else {
        return;
    };
    kb.to_text();
    // Names to use as arguments: some of the KB's own, and a few others.
    let text = kb.to_text();
    let mut names: Vec<String> = vec!["top".into(), "x".into(), "not(x)".into(), "[a,b]".into()];
    for part in text.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
        if !part.is_empty() && part.chars().next().is_some_and(|c| c.is_ascii_lowercase()) && names.len() < 12 {
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
    for (k, u) in UPDATES.iter().enumerate() {
        let mut copy = kb.clone();
        let args: Vec<String> = (0..u.arity)
            .map(|i| names[(k + 2 * i) % names.len()].clone())
            .collect();
        let text = format!("{}({})", u.name, args.join(","));
        if let Ok(clause) = sitlog_syntax::read_term(&text) {
            if copy.update(&clause).is_ok() {
                Kb::parse(&copy.to_text(), "again").expect("a KB after an update saves to text that loads");
            }
        }
    }
});
