//! `sitlogc run --view`: the page and the event stream over loopback; the
//! current situation advances; the server stops when the task ends.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::Stdio;
use std::time::Duration;

use crate::support::sitlogc;

/// One GET over loopback: status line and body.
fn get(addr: &str, path: &str) -> std::io::Result<(String, String)> {
    let mut s = TcpStream::connect(addr)?;
    s.set_read_timeout(Some(Duration::from_secs(60)))?;
    write!(s, "GET {path} HTTP/1.1\r\nHost: {addr}\r\n\r\n")?;
    let mut all = String::new();
    s.read_to_string(&mut all)?;
    let (head, body) = all.split_once("\r\n\r\n").unwrap_or((&all, ""));
    Ok((
        head.lines().next().unwrap_or("").to_owned(),
        body.to_owned(),
    ))
}

#[test]
fn live_view_follows_the_run() {
    let mut child = sitlogc()
        .args([
            "run",
            "../dms/examples/appendix_a",
            "--script",
            "../dms/examples/appendix_a/script.txt",
            "--format",
            "json",
            "--view",
            "--view-delay",
            "20",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    let addr = loop {
        line.clear();
        assert!(
            stderr.read_line(&mut line).unwrap() > 0,
            "no live view address"
        );
        if let Some(at) = line.find("http://127.0.0.1:") {
            let rest = &line[at + "http://".len()..];
            break rest[..rest.find('/').unwrap()].to_owned();
        }
    };
    // the page: the diagram inline, the script that follows the run, nothing from elsewhere
    let (status, page) = get(&addr, "/").unwrap();
    assert!(status.contains("200"), "{status}");
    assert!(page.contains("<svg") && page.contains("EventSource(\"/events\")"));
    assert!(page.contains(r#"id="d0.s0""#));
    assert!(!page.contains("https://") && !page.contains("src=\"http"));
    let (status, svg) = get(&addr, "/diagram.svg").unwrap();
    assert!(status.contains("200") && svg.starts_with("<svg"));
    let (status, _) = get(&addr, "/nope").unwrap();
    assert!(status.contains("404"));
    // the event stream (the task starts now), to its end
    let (status, stream) = get(&addr, "/events").unwrap();
    assert!(status.contains("200"));
    let events: Vec<serde_json::Value> = stream
        .lines()
        .filter_map(|l| l.strip_prefix("data: "))
        .map(|d| serde_json::from_str(d).unwrap())
        .collect();
    let (end, transitions) = events.split_last().unwrap();
    assert_eq!(end["end"], true);
    assert_eq!(end["status"], "ok");
    assert_eq!(transitions.len(), 12);
    let nodes: Vec<&str> = transitions
        .iter()
        .map(|e| e["node"].as_str().unwrap())
        .collect();
    // it advances: is, is, wait's is, fs2, rs, ..., fs
    assert_eq!(nodes[0], "d0.s0");
    assert_eq!(nodes[2], "d1.s0");
    assert_eq!(nodes[11], "d0.s2");
    assert_eq!(transitions[2]["stack"], serde_json::json!(["main", "wait"]));
    assert_eq!(
        transitions[1]["edges"],
        serde_json::json!(["e:d0.s0.a2", "e:d0.s0.a2.f.x1"])
    );
    for (i, e) in transitions.iter().enumerate() {
        assert_eq!(e["seq"], i);
    }
    // the task ends, and so does the server
    let status = child.wait().unwrap();
    assert!(status.success());
    let mut out = String::new();
    child
        .stdout
        .take()
        .unwrap()
        .read_to_string(&mut out)
        .unwrap();
    assert!(out.contains("\"status\":\"ok\""));
    assert!(
        TcpStream::connect(&addr).is_err(),
        "the server still listens"
    );
}

#[test]
fn view_options_need_view() {
    let out = sitlogc()
        .args(["run", "../dms/examples/appendix_a", "--view-port", "1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
