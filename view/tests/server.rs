//! The view server on its own: routes, replay of past events, end, stop.

use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::Observer;
use sitlog_runtime::{Atom, Store, Term};
use sitlog_view::View;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::Duration;

fn request(addr: std::net::SocketAddr, head: &str) -> String {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    s.write_all(head.as_bytes()).unwrap();
    let mut all = String::new();
    s.read_to_string(&mut all).unwrap();
    all
}

fn diagram() -> sitlog_graph::Diagram {
    sitlog_graph::Diagram {
        title: "t<&>".into(),
        ..Default::default()
    }
}

#[test]
fn routes_replay_and_stop() {
    let view = View::start(diagram(), 0).unwrap();
    let addr = view.addr();
    assert!(view.url().starts_with("http://127.0.0.1:"));
    let host = format!("Host: {addr}\r\n");
    let req = |line: &str| request(addr, &format!("{line}\r\n{host}\r\n"));
    let page = req("GET / HTTP/1.1");
    assert!(page.starts_with("HTTP/1.1 200 OK"));
    assert!(page.contains("t&lt;&amp;&gt;"));
    assert!(req("POST / HTTP/1.1").starts_with("HTTP/1.1 405"));
    assert!(request(addr, "garbage\r\n\r\n").starts_with("HTTP/1.1 400"));
    let state = req("GET /state HTTP/1.1");
    assert!(state.contains(r#"{"transitions":0,"ended":false,"last":null}"#));
    assert!(!view.wait_for_viewer(Some(Duration::from_millis(50))));
    // two transitions before anyone looks: a late page still gets them
    let mut obs = view.observer(Duration::ZERO);
    let mut store = Store::new();
    let main = Term::atom(Atom::intern("main"));
    let is = Term::atom(Atom::intern("is"));
    let go = Term::atom(Atom::intern("go"));
    let entry = Entry {
        dm: main,
        situation: is,
        expectation: go,
        action: store.list(&[]),
    };
    obs.transition(&store, &entry, 0, Some(is));
    obs.transition(&store, &entry, 0, None);
    let state = req("GET /state HTTP/1.1");
    assert!(state.contains(r#""transitions":2"#), "{state}");
    let reader = std::thread::spawn(move || {
        request(
            addr,
            &format!("GET /events HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
        )
    });
    assert!(view.wait_for_viewer(Some(Duration::from_secs(10))));
    view.finish("ok", "done", Duration::from_secs(5));
    let stream = reader.join().unwrap();
    let data: Vec<&str> = stream.lines().filter(|l| l.starts_with("data: ")).collect();
    assert_eq!(data.len(), 3, "{stream}");
    assert!(data[0].contains(r#""situation":"is""#));
    assert!(data[2].contains(r#""end":true"#));
    assert!(TcpStream::connect(addr).is_err());
}

/// DNS rebinding and cross-site requests (issue 31): a `Host` naming
/// another server and an `Origin` of another site are refused; the served
/// names are answered.
#[test]
fn only_its_own_host_and_origin_are_answered() {
    let view = View::start(diagram(), 0).unwrap();
    let addr = view.addr();
    let port = addr.port();
    let get = |headers: &str| request(addr, &format!("GET /state HTTP/1.1\r\n{headers}\r\n"));
    for ok in [
        format!("Host: 127.0.0.1:{port}\r\n"),
        format!("Host: localhost:{port}\r\n"),
        format!("Host: localhost:{port}\r\nOrigin: http://localhost:{port}\r\n"),
        format!("Host: 127.0.0.1:{port}\r\nOrigin: http://127.0.0.1:{port}\r\n"),
    ] {
        assert!(get(&ok).starts_with("HTTP/1.1 200"), "{ok}");
    }
    for bad in [
        format!("Host: evil.example.com:{port}\r\n"),
        "Host: evil.example.com\r\n".to_owned(),
        "Host: 127.0.0.1:1\r\n".to_owned(),
        format!("Host: 127.0.0.1:{port}\r\nOrigin: http://evil.example.com\r\n"),
        format!("Host: 127.0.0.1:{port}\r\nOrigin: https://127.0.0.1:{port}\r\n"),
        format!("Host: 127.0.0.1:{port}\r\nOrigin: null\r\n"),
        // issue 38: two Hosts (a foreign one first), none, two Origins
        format!("Host: evil.example.com\r\nHost: 127.0.0.1:{port}\r\n"),
        format!("Host: 127.0.0.1:{port}\r\nHost: evil.example.com\r\n"),
        String::new(),
        format!("Host: 127.0.0.1:{port}\r\nOrigin: http://evil.example.com\r\nOrigin: http://127.0.0.1:{port}\r\n"),
    ] {
        let answer = get(&bad);
        assert!(answer.starts_with("HTTP/1.1 403"), "{bad}: {answer}");
    }
    // HTTP/1.0 without a Host
    let answer = request(addr, "GET /state HTTP/1.0\r\n\r\n");
    assert!(answer.starts_with("HTTP/1.1 403"), "{answer}");
    // a cross-site event stream does not count as a viewer (it would start the task)
    let answer = request(
        addr,
        &format!("GET /events HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nOrigin: http://evil.example.com\r\n\r\n"),
    );
    assert!(answer.starts_with("HTTP/1.1 403"), "{answer}");
    assert!(!view.wait_for_viewer(Some(Duration::from_millis(50))));
}

/// A long run keeps the last `WINDOW` events only: a late page gets those,
/// numbered from where they are in the run.
#[test]
fn a_long_run_keeps_a_bounded_window() {
    let view = View::start(diagram(), 0).unwrap();
    let addr = view.addr();
    let mut obs = view.observer(Duration::ZERO);
    let mut store = Store::new();
    let main = Term::atom(Atom::intern("main"));
    let entry = Entry {
        dm: main,
        situation: main,
        expectation: main,
        action: store.list(&[]),
    };
    let n = sitlog_view::WINDOW + 25;
    for _ in 0..n {
        obs.transition(&store, &entry, 0, Some(main));
    }
    let state = request(
        addr,
        &format!("GET /state HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
    );
    assert!(state.contains(&format!(r#""transitions":{n}"#)), "{state}");
    let reader = std::thread::spawn(move || {
        request(
            addr,
            &format!("GET /events HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
        )
    });
    assert!(view.wait_for_viewer(Some(Duration::from_secs(10))));
    view.finish("ok", "done", Duration::from_secs(5));
    let stream = reader.join().unwrap();
    let data: Vec<&str> = stream.lines().filter(|l| l.starts_with("data: ")).collect();
    // the page opened before the end: it gets the window, then the end (one
    // more event) unless the end came before its first read
    let w = sitlog_view::WINDOW;
    assert!(
        data.len() == w || data.len() == w + 1,
        "the window, the end event included: {}",
        data.len()
    );
    // events are numbered from 0; the end is number n
    let first = n + 1 - data.len();
    assert!(
        data[0].contains(&format!(r#""seq":{first},"#))
            || data[0].contains(&format!(r#""seq":{first}}}"#)),
        "{}",
        data[0]
    );
    assert!(data[data.len() - 1].contains(r#""end":true"#));
}
