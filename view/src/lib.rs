//! `sitlog-view`: the live view of a running task (`sitlogc run --view`).
//!
//! A small HTTP server on 127.0.0.1 only serves the program's diagram (the
//! SVG of `sitlog-graph`) in a page that highlights, as the task runs, the
//! current situation, the arcs taken, the DM stack and the last
//! transitions. The page reads the transitions as Server-Sent Events
//! (`/events`), the same events `--trace` writes (one JSON object per
//! transition), and works offline (no script or style from elsewhere).
//!
//! Routes: `/` the page, `/diagram.svg`, `/events` (an event stream that
//! replays the last [`WINDOW`] transitions, then follows the run, and ends
//! with `{"end":true,...}`), `/state` (the last transition, JSON). Only
//! requests with one `Host` naming this server on 127.0.0.1 or localhost,
//! and at most one `Origin`, this server's, are answered: another site's
//! page cannot read or start a task by DNS rebinding or a cross-origin
//! request.
//!
//! **Invariant:** the server only reads; it never changes the run. The
//! observer it hands out costs one JSON line and a lock per transition.
//! The server is ours (std's `TcpListener`, GET only, one thread per
//! connection): an event stream must be written unbuffered as it happens,
//! and nothing more is needed on a loopback port; requests are parsed by
//! `httparse` (issue 38), so that the header rules are not ours to get
//! wrong.

use sitlog_graph::trace::{chain, find_dm, find_situation};
use sitlog_graph::Diagram;
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::Observer;
use sitlog_runtime::{Store, Term};
use std::io::{self, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

const PAGE: &str = include_str!("page.html");

/// How many of the last events the server keeps for pages that open late
/// (as the debugger keeps a bounded history): memory stays flat however
/// long the run, and a page opened during the run sees it from then on.
pub const WINDOW: usize = 10_000;

#[derive(Default)]
struct State {
    /// The last [`WINDOW`] events (JSON, one line each); the last one may be
    /// the end.
    events: std::collections::VecDeque<String>,
    /// How many events came before `events[0]`.
    dropped: usize,
    ended: bool,
    stopping: bool,
    /// Event streams opened, and those that have sent the end.
    viewers: usize,
    viewers_done: usize,
}

struct Shared {
    state: Mutex<State>,
    /// The served port (requests must name it in `Host` and `Origin`).
    port: u16,
    changed: Condvar,
    diagram: Diagram,
    page: String,
    svg: String,
}

impl Shared {
    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl State {
    /// Every event so far, the dropped ones included.
    fn total(&self) -> usize {
        self.dropped + self.events.len()
    }

    /// Keeps `event`, dropping the oldest beyond [`WINDOW`].
    fn push(&mut self, event: String) {
        self.events.push_back(event);
        if self.events.len() > WINDOW {
            self.events.pop_front();
            self.dropped += 1;
        }
    }
}

/// A running view server.
pub struct View {
    addr: SocketAddr,
    shared: Arc<Shared>,
    acceptor: Option<JoinHandle<()>>,
}

/// Escapes text for HTML.
fn esc(s: &str) -> String {
    sitlog_graph::svg::esc(s)
}

impl View {
    /// Serves `diagram` on 127.0.0.1:`port` (0: any free port).
    pub fn start(diagram: Diagram, port: u16) -> io::Result<View> {
        let listener = TcpListener::bind(("127.0.0.1", port))?;
        let addr = listener.local_addr()?;
        let layout = sitlog_graph::layout::layout(&diagram);
        let svg = sitlog_graph::svg::render(&diagram, &layout, None);
        let page = PAGE
            .replace("{{TITLE}}", &esc(&diagram.title))
            .replace("{{SVG}}", &svg);
        let shared = Arc::new(Shared {
            state: Mutex::new(State::default()),
            port: addr.port(),
            changed: Condvar::new(),
            diagram,
            page,
            svg,
        });
        let s = shared.clone();
        let acceptor = std::thread::Builder::new()
            .name("sitlog-view".to_owned())
            .spawn(move || accept(listener, s))?;
        Ok(View {
            addr,
            shared,
            acceptor: Some(acceptor),
        })
    }

    /// Where the page is.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Notes from laying out the diagram are the caller's to show; this
    /// is the observer to give the run. `delay` slows each transition so
    /// that a person can follow a fast task.
    pub fn observer(&self, delay: Duration) -> ViewObserver {
        ViewObserver {
            shared: self.shared.clone(),
            stack: Vec::new(),
            delay,
        }
    }

    /// Waits until a page follows the run (an event stream is open), at
    /// most `timeout` (`None`: for ever). Whether one is.
    pub fn wait_for_viewer(&self, timeout: Option<Duration>) -> bool {
        let start = Instant::now();
        let mut st = self.shared.lock();
        while st.viewers == 0 {
            let left = match timeout {
                Some(t) => match t.checked_sub(start.elapsed()) {
                    Some(l) if !l.is_zero() => l,
                    _ => return false,
                },
                None => Duration::from_secs(1),
            };
            st = self
                .shared
                .changed
                .wait_timeout(st, left)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
        true
    }

    /// Ends the view: sends the end event (with `status` and `message`),
    /// lets open pages read it (at most `linger`), then stops the server.
    pub fn finish(mut self, status: &str, message: &str, linger: Duration) {
        {
            let mut st = self.shared.lock();
            let end = serde_json::json!({"end": true, "status": status, "message": message});
            st.push(end.to_string());
            st.ended = true;
            self.shared.changed.notify_all();
        }
        let start = Instant::now();
        let mut st = self.shared.lock();
        while st.viewers_done < st.viewers && start.elapsed() < linger {
            st = self
                .shared
                .changed
                .wait_timeout(st, Duration::from_millis(50))
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
        drop(st);
        self.stop();
    }

    fn stop(&mut self) {
        {
            let mut st = self.shared.lock();
            st.stopping = true;
            self.shared.changed.notify_all();
        }
        // the acceptor sees `stopping` within its polling interval
        if let Some(h) = self.acceptor.take() {
            let _ = h.join();
        }
    }
}

impl Drop for View {
    fn drop(&mut self) {
        if self.acceptor.is_some() {
            self.stop();
        }
    }
}

/// Feeds a [`View`] with the run's transitions.
pub struct ViewObserver {
    shared: Arc<Shared>,
    /// DM names by depth.
    stack: Vec<String>,
    delay: Duration,
}

impl Observer for ViewObserver {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        let dm = store.writeq(entry.dm);
        let situation = store.writeq(entry.situation);
        let next = next.map(|n| store.writeq(n));
        self.stack.truncate(depth);
        while self.stack.len() < depth {
            self.stack.push("?".to_owned());
        }
        self.stack.push(dm.clone());
        let d = &self.shared.diagram;
        let g = find_dm(d, &dm);
        let node = g.and_then(|g| find_situation(g, &situation));
        let expectation = store.writeq(entry.expectation);
        let edges = match (g, node, next.as_deref()) {
            (Some(g), Some(n), Some(next)) => find_situation(g, next)
                .and_then(|t| chain(g, &n.id, &t.id, Some(&expectation)))
                .unwrap_or_default(),
            _ => Vec::new(),
        };
        {
            let mut st = self.shared.lock();
            let ev = serde_json::json!({
                "seq": st.total(),
                "dm": dm,
                "situation": situation,
                "expectation": expectation,
                "action": store.writeq(entry.action),
                "depth": depth,
                "next": next,
                "node": node.map(|n| n.id.clone()),
                "edges": edges,
                "stack": self.stack,
            });
            st.push(ev.to_string());
            self.shared.changed.notify_all();
        }
        if !self.delay.is_zero() {
            std::thread::sleep(self.delay);
        }
    }
}

/// Accepts connections until the view stops. The listener does not block,
/// so that stopping needs no connection to wake it: a sandboxed run
/// (`sitlog_robot::sandbox`) may open no socket by then.
fn accept(listener: TcpListener, shared: Arc<Shared>) {
    let polled = listener.set_nonblocking(true).is_ok();
    loop {
        if shared.lock().stopping {
            break;
        }
        let stream = match listener.accept() {
            Ok((stream, _)) => stream,
            Err(e) if e.kind() == io::ErrorKind::WouldBlock => {
                std::thread::sleep(Duration::from_millis(20));
                continue;
            }
            Err(_) if !polled => break,
            Err(_) => {
                std::thread::sleep(Duration::from_millis(20));
                continue;
            }
        };
        // Connections block (as the request handling expects).
        if stream.set_nonblocking(false).is_err() {
            continue;
        }
        let s = shared.clone();
        let _ = std::thread::Builder::new()
            .name("sitlog-view-conn".to_owned())
            .spawn(move || {
                let _ = handle(stream, &s);
            });
    }
}

/// A request's head: the path of a GET (`None` for another method), its
/// `Host` and `Origin` headers (every one sent), or `None` when it is not
/// an HTTP request.
struct Head {
    get: Option<String>,
    hosts: Vec<String>,
    origins: Vec<String>,
}

/// The largest request head read.
const MAX_HEAD: usize = 64 * 1024;

/// Reads the request head (at most [`MAX_HEAD`] bytes, 5 s) and parses it
/// (`httparse`); `Ok(None)` for bytes that are not an HTTP request head.
fn request_head(mut stream: &TcpStream) -> io::Result<Option<Head>> {
    stream.set_read_timeout(Some(Duration::from_secs(5)))?;
    let mut buf = Vec::with_capacity(1024);
    let mut chunk = [0u8; 4096];
    loop {
        let n = stream.read(&mut chunk)?;
        if n == 0 {
            break;
        }
        let from = buf.len().saturating_sub(3);
        buf.extend_from_slice(&chunk[..n]);
        if buf[from..].windows(4).any(|w| w == b"\r\n\r\n")
            || buf[from..].windows(2).any(|w| w == b"\n\n")
            || buf.len() > MAX_HEAD
        {
            break;
        }
    }
    let mut headers = [httparse::EMPTY_HEADER; 64];
    let mut request = httparse::Request::new(&mut headers);
    match request.parse(&buf) {
        Ok(httparse::Status::Complete(_)) => {}
        _ => return Ok(None),
    }
    let text = |v: &[u8]| String::from_utf8_lossy(v).trim().to_owned();
    let named = |name: &str| -> Vec<String> {
        request
            .headers
            .iter()
            .filter(|h| h.name.eq_ignore_ascii_case(name))
            .map(|h| text(h.value))
            .collect()
    };
    let (hosts, origins) = (named("host"), named("origin"));
    let get = match (request.method, request.path) {
        (Some("GET"), Some(path)) => Some(path.to_owned()),
        _ => None,
    };
    Ok(Some(Head {
        get,
        hosts,
        origins,
    }))
}

/// The names a page of this server is reached by: `127.0.0.1`, `localhost`
/// (and `[::1]`), with the served port.
fn own_host(host: &str, port: u16) -> bool {
    let (name, p) = match host.rsplit_once(':') {
        Some((name, p)) if !name.ends_with(']') || name.starts_with('[') => (name, p),
        _ => return false,
    };
    p.parse::<u16>() == Ok(port)
        && (name == "127.0.0.1" || name.eq_ignore_ascii_case("localhost") || name == "[::1]")
}

/// Whether a request may be answered: exactly one `Host`, naming this
/// server (a `Host` naming another server is a page of another site
/// reaching this one by DNS rebinding; none, as HTTP/1.0 allows, or two,
/// leave the server to guess), and at most one `Origin`, this server's (a
/// cross-site `fetch` or `EventSource` sends its own).
fn allowed(head: &Head, port: u16) -> bool {
    let host_ok = matches!(head.hosts.as_slice(), [h] if own_host(h, port));
    let origin_ok = match head.origins.as_slice() {
        [] => true,
        [o] => o
            .strip_prefix("http://")
            .is_some_and(|rest| own_host(rest.trim_end_matches('/'), port)),
        _ => false,
    };
    host_ok && origin_ok
}

fn respond(mut stream: &TcpStream, status: &str, kind: &str, body: &[u8]) -> io::Result<()> {
    write!(
        stream,
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(body)?;
    stream.flush()
}

fn handle(stream: TcpStream, shared: &Shared) -> io::Result<()> {
    let Some(head) = request_head(&stream)? else {
        return respond(
            &stream,
            "400 Bad Request",
            "text/plain",
            b"not an HTTP request\n",
        );
    };
    if !allowed(&head, shared.port) {
        return respond(
            &stream,
            "403 Forbidden",
            "text/plain",
            b"this live view answers only pages it served itself (one Host, and at most one Origin, 127.0.0.1 or localhost)\n",
        );
    }
    let Some(path) = head.get else {
        return respond(
            &stream,
            "405 Method Not Allowed",
            "text/plain",
            b"GET only\n",
        );
    };
    let path = path.split('?').next().unwrap_or("");
    match path {
        "/" | "/index.html" => respond(
            &stream,
            "200 OK",
            "text/html; charset=utf-8",
            shared.page.as_bytes(),
        ),
        "/diagram.svg" => respond(&stream, "200 OK", "image/svg+xml", shared.svg.as_bytes()),
        "/state" => {
            let st = shared.lock();
            let last = st
                .events
                .back()
                .cloned()
                .unwrap_or_else(|| "null".to_owned());
            let body = format!(
                "{{\"transitions\":{},\"ended\":{},\"last\":{last}}}\n",
                st.total() - usize::from(st.ended),
                st.ended
            );
            drop(st);
            respond(&stream, "200 OK", "application/json", body.as_bytes())
        }
        "/events" => events(stream, shared),
        _ => respond(&stream, "404 Not Found", "text/plain", b"not found\n"),
    }
}

/// The event stream: every event so far, then each new one, until the end.
fn events(mut stream: TcpStream, shared: &Shared) -> io::Result<()> {
    stream.set_write_timeout(Some(Duration::from_secs(10)))?;
    write!(
        stream,
        "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n"
    )?;
    stream.flush()?;
    {
        let mut st = shared.lock();
        st.viewers += 1;
        shared.changed.notify_all();
    }
    let mut sent = 0;
    let result = loop {
        let (batch, done) = {
            let mut st = shared.lock();
            while sent >= st.total() && !st.stopping {
                st = shared
                    .changed
                    .wait_timeout(st, Duration::from_secs(15))
                    .unwrap_or_else(|e| e.into_inner())
                    .0;
                if sent >= st.total() {
                    break;
                }
            }
            // a page that fell behind the window goes on from its start
            sent = sent.max(st.dropped);
            let batch: Vec<String> = st.events.range(sent - st.dropped..).cloned().collect();
            // once ended, the batch holds everything up to the end event
            (batch, st.stopping || st.ended)
        };
        let mut out = String::new();
        if batch.is_empty() && !done {
            out.push_str(": still here\n\n");
        }
        for e in &batch {
            out.push_str("data: ");
            out.push_str(e);
            out.push_str("\n\n");
        }
        sent += batch.len();
        if let Err(e) = stream
            .write_all(out.as_bytes())
            .and_then(|_| stream.flush())
        {
            break Err(e);
        }
        if done {
            break Ok(());
        }
    };
    let mut st = shared.lock();
    st.viewers_done += 1;
    shared.changed.notify_all();
    result
}
