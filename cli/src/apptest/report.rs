//! What `sitlogc test` prints: cargo's habits in text (`test NAME ... ok`,
//! the failures with their detail, `test result: ok. N passed; M failed`),
//! one JSON object per line with `--format json`, and JUnit XML for CI
//! (`--junit FILE`).

use super::run::Outcome;
use std::time::Duration;

/// The line of one test: `test NAME ... ok` / `FAILED`.
pub fn line(o: &Outcome) -> String {
    let status = if o.passed() { "ok" } else { "FAILED" };
    format!("test {} ... {status}\n", o.name)
}

/// The failures' details, their names, and the summary.
pub fn summary(outcomes: &[Outcome], filtered: usize, elapsed: Duration) -> String {
    let failed: Vec<&Outcome> = outcomes.iter().filter(|o| !o.passed()).collect();
    let mut s = String::new();
    if !failed.is_empty() {
        s.push_str("\nfailures:\n");
        for o in &failed {
            s.push_str(&format!("\n---- {} ({}) ----\n", o.name, o.file));
            for f in &o.failures {
                s.push_str(f);
                s.push('\n');
            }
            if !o.detail.is_empty() {
                s.push_str(&o.detail);
            }
        }
        s.push_str("\nfailures:\n");
        for o in &failed {
            s.push_str(&format!("    {}\n", o.name));
        }
    }
    let result = if failed.is_empty() { "ok" } else { "FAILED" };
    s.push_str(&format!(
        "\ntest result: {result}. {} passed; {} failed; {filtered} filtered out; finished in {:.2}s\n",
        outcomes.len() - failed.len(),
        failed.len(),
        elapsed.as_secs_f64()
    ));
    s
}

/// `--format json`: the object of one test.
pub fn json_line(o: &Outcome) -> String {
    serde_json::json!({
        "type": "test",
        "name": o.name,
        "file": o.file,
        "status": if o.passed() { "ok" } else { "failed" },
        "failures": o.failures,
        "detail": o.detail,
        "transitions": o.transitions,
        "seconds": o.elapsed.as_secs_f64(),
    })
    .to_string()
        + "\n"
}

/// `--format json`: the summary (and the coverage, when asked for).
pub fn json_summary(
    outcomes: &[Outcome],
    filtered: usize,
    elapsed: Duration,
    coverage: Option<serde_json::Value>,
) -> String {
    let failed = outcomes.iter().filter(|o| !o.passed()).count();
    let mut v = serde_json::json!({
        "type": "summary",
        "status": if failed == 0 { "ok" } else { "failed" },
        "passed": outcomes.len() - failed,
        "failed": failed,
        "filtered_out": filtered,
        "seconds": elapsed.as_secs_f64(),
    });
    if let Some(c) = coverage {
        v["coverage"] = c;
    }
    v.to_string() + "\n"
}

fn xml(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            // characters XML 1.0 cannot hold
            c if (c as u32) < 0x20 && !matches!(c, '\n' | '\r' | '\t') => {
                s.push_str(&format!("\\u{{{:x}}}", c as u32))
            }
            c => s.push(c),
        }
    }
    s
}

/// JUnit XML: one `testsuite` named after the application, one `testcase`
/// per test, a `failure` with its messages and detail, the run's output
/// as `system-out`.
pub fn junit(suite: &str, outcomes: &[Outcome], elapsed: Duration) -> String {
    let failed = outcomes.iter().filter(|o| !o.passed()).count();
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    s.push_str(&format!(
        "<testsuites tests=\"{}\" failures=\"{failed}\" time=\"{:.3}\">\n",
        outcomes.len(),
        elapsed.as_secs_f64()
    ));
    s.push_str(&format!(
        "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failed}\" errors=\"0\" time=\"{:.3}\">\n",
        xml(suite),
        outcomes.len(),
        elapsed.as_secs_f64()
    ));
    for o in outcomes {
        s.push_str(&format!(
            "    <testcase name=\"{}\" classname=\"{}\" file=\"{}\" time=\"{:.3}\">\n",
            xml(&o.name),
            xml(suite),
            xml(&o.file),
            o.elapsed.as_secs_f64()
        ));
        if !o.passed() {
            s.push_str(&format!(
                "      <failure message=\"{}\">{}\n{}</failure>\n",
                xml(o.failures.first().map(String::as_str).unwrap_or("")),
                xml(&o.failures.join("\n")),
                xml(&o.detail)
            ));
        }
        s.push_str(&format!(
            "      <system-out>{}</system-out>\n",
            xml(&o.stdout)
        ));
        s.push_str("    </testcase>\n");
    }
    s.push_str("  </testsuite>\n</testsuites>\n");
    s
}
