//! `sitlog-lsp`: the language server protocol around an [`Analyzer`]. This
//! crate owns the protocol only: the document store (the editor's unsaved
//! text, an overlay over the disk), URIs and UTF-16 positions, and which
//! notifications and requests are answered. It knows nothing of SitLog:
//! `sitlogc lsp` supplies the analysis (`sitlog_cli::analysis`, over the
//! compiler core).
//!
//! Invariants: every file the analyzer reported diagnostics for is told
//! again when they are gone (an empty list), so an editor never keeps a
//! stale error; a request the server does not know gets the protocol's
//! `MethodNotFound` error, never a hang; a request with bad parameters gets
//! `InvalidParams` and the server goes on (text that is not JSON-RPC at
//! all ends the session with an error message and exit status 2).
//!
//! Documents are `file:` URIs, or `untitled:` ones (an unsaved buffer,
//! [`document_path`]).
//!
//! Served: `textDocument/didOpen`, `didChange` (full text), `didSave`,
//! `didClose`; `textDocument/publishDiagnostics`; `textDocument/definition`;
//! `textDocument/hover`; `shutdown`/`exit`.

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use serde_json::{json, Value};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};

/// The editor's text of open documents, by path.
pub type Overlay = HashMap<PathBuf, String>;

/// A position: 0-based line and UTF-16 column, as the protocol counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Pos {
    pub line: u32,
    pub character: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Range {
    pub start: Pos,
    pub end: Pos,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// One diagnostic of a file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diag {
    pub range: Range,
    pub severity: Severity,
    pub code: String,
    pub message: String,
}

/// What the server asks of the language.
pub trait Analyzer {
    /// The diagnostics of the program `file` belongs to, for every file of
    /// that program (files without any may be left out).
    fn diagnostics(&self, file: &Path, overlay: &Overlay) -> Vec<(PathBuf, Vec<Diag>)>;
    /// Where the name at `pos` is defined.
    fn definition(&self, file: &Path, pos: Pos, overlay: &Overlay) -> Option<(PathBuf, Range)>;
    /// Markdown about the name at `pos`.
    fn hover(&self, file: &Path, pos: Pos, overlay: &Overlay) -> Option<String>;
}

pub mod transport;

/// Serves on stdin/stdout until the client says `exit`, reading messages
/// of at most `max_message_bytes` (see [`transport`]).
pub fn run_stdio(analyzer: &dyn Analyzer, max_message_bytes: u64) -> Result<(), String> {
    let (connection, threads) = transport::stdio(max_message_bytes).map_err(|e| e.to_string())?;
    let served = serve(&connection, analyzer);
    drop(connection);
    let read = threads.join().map_err(|e| e.to_string());
    // a broken frame ends the session: its error says why
    read.and(served)
}

fn capabilities() -> Value {
    json!({
        "textDocumentSync": { "openClose": true, "change": 1, "save": { "includeText": false } },
        "definitionProvider": true,
        "hoverProvider": true,
    })
}

/// Serves one client on `connection`: the initialize handshake, then
/// messages until `shutdown` and `exit`.
pub fn serve(connection: &Connection, analyzer: &dyn Analyzer) -> Result<(), String> {
    let (id, _params) = connection.initialize_start().map_err(|e| e.to_string())?;
    connection
        .initialize_finish(
            id,
            json!({
                "capabilities": capabilities(),
                "serverInfo": { "name": "sitlogc", "version": env!("CARGO_PKG_VERSION") },
            }),
        )
        .map_err(|e| e.to_string())?;
    let mut server = Server {
        analyzer,
        overlay: Overlay::new(),
        published: BTreeMap::new(),
    };
    for msg in &connection.receiver {
        match msg {
            Message::Request(req) => {
                if connection
                    .handle_shutdown(&req)
                    .map_err(|e| e.to_string())?
                {
                    return Ok(());
                }
                let resp = server.request(req);
                connection
                    .sender
                    .send(Message::Response(resp))
                    .map_err(|e| e.to_string())?;
            }
            Message::Notification(n) => {
                for out in server.notification(n) {
                    connection
                        .sender
                        .send(Message::Notification(out))
                        .map_err(|e| e.to_string())?;
                }
            }
            Message::Response(_) => {}
        }
    }
    Ok(())
}

struct Server<'a> {
    analyzer: &'a dyn Analyzer,
    overlay: Overlay,
    /// Per program root file: the files it last had diagnostics for.
    published: BTreeMap<PathBuf, BTreeSet<PathBuf>>,
}

impl Server<'_> {
    fn request(&mut self, req: Request) -> Response {
        let id = req.id.clone();
        let params = &req.params;
        let position = || -> Result<(PathBuf, Pos), String> {
            let uri = params["textDocument"]["uri"]
                .as_str()
                .ok_or("missing textDocument.uri")?;
            let path = document_path(uri).ok_or_else(|| format!("not a file URI: {uri}"))?;
            let p = &params["position"];
            let (Some(line), Some(character)) = (p["line"].as_u64(), p["character"].as_u64())
            else {
                return Err("missing position".into());
            };
            Ok((
                path,
                Pos {
                    line: line as u32,
                    character: character as u32,
                },
            ))
        };
        match req.method.as_str() {
            "textDocument/definition" => match position() {
                Ok((path, pos)) => {
                    let result = match self.analyzer.definition(&path, pos, &self.overlay) {
                        Some((file, range)) => json!({
                            "uri": document_uri(&file),
                            "range": range_json(range),
                        }),
                        None => Value::Null,
                    };
                    Response::new_ok(id, result)
                }
                Err(e) => Response::new_err(id, ErrorCode::InvalidParams as i32, e),
            },
            "textDocument/hover" => match position() {
                Ok((path, pos)) => {
                    let result = match self.analyzer.hover(&path, pos, &self.overlay) {
                        Some(text) => json!({
                            "contents": { "kind": "markdown", "value": text },
                        }),
                        None => Value::Null,
                    };
                    Response::new_ok(id, result)
                }
                Err(e) => Response::new_err(id, ErrorCode::InvalidParams as i32, e),
            },
            m => Response::new_err(
                id,
                ErrorCode::MethodNotFound as i32,
                format!("sitlogc lsp does not serve `{m}`"),
            ),
        }
    }

    fn notification(&mut self, n: Notification) -> Vec<Notification> {
        let doc = &n.params["textDocument"];
        let Some(path) = doc["uri"].as_str().and_then(document_path) else {
            return Vec::new();
        };
        match n.method.as_str() {
            "textDocument/didOpen" => {
                if let Some(text) = doc["text"].as_str() {
                    self.overlay.insert(path.clone(), text.to_owned());
                }
            }
            "textDocument/didChange" => {
                // Full sync: the last change holds the whole text.
                let changes = n.params["contentChanges"].as_array();
                if let Some(text) = changes
                    .and_then(|c| c.last())
                    .and_then(|c| c["text"].as_str())
                {
                    self.overlay.insert(path.clone(), text.to_owned());
                }
            }
            "textDocument/didClose" => {
                self.overlay.remove(&path);
            }
            "textDocument/didSave" => {}
            _ => return Vec::new(),
        }
        self.publish(&path)
    }

    /// Diagnostics of `path`'s program, and empty lists for the files that
    /// had some and have none now.
    fn publish(&mut self, path: &Path) -> Vec<Notification> {
        let results = self.analyzer.diagnostics(path, &self.overlay);
        let now: BTreeSet<PathBuf> = results.iter().map(|(p, _)| p.clone()).collect();
        let before = self.published.insert(path.to_path_buf(), now.clone());
        let mut out: Vec<Notification> = results
            .into_iter()
            .map(|(file, diags)| publish_diagnostics(&file, &diags))
            .collect();
        for gone in before.unwrap_or_default().difference(&now) {
            out.push(publish_diagnostics(gone, &[]));
        }
        out
    }
}

fn publish_diagnostics(file: &Path, diags: &[Diag]) -> Notification {
    let items: Vec<Value> = diags
        .iter()
        .map(|d| {
            json!({
                "range": range_json(d.range),
                "severity": match d.severity { Severity::Error => 1, Severity::Warning => 2 },
                "code": d.code,
                "source": "sitlogc",
                "message": d.message,
            })
        })
        .collect();
    Notification::new(
        "textDocument/publishDiagnostics".into(),
        json!({ "uri": document_uri(file), "diagnostics": items }),
    )
}

fn range_json(r: Range) -> Value {
    json!({
        "start": { "line": r.start.line, "character": r.start.character },
        "end": { "line": r.end.line, "character": r.end.character },
    })
}

/// The path that stands for a document: its file for a `file:` URI; for
/// an `untitled:` document (a buffer never saved), the URI itself as a
/// relative path (`untitled:Untitled-1`), which has no directory.
pub fn document_path(uri: &str) -> Option<PathBuf> {
    if uri.starts_with(UNTITLED) {
        return Some(PathBuf::from(uri));
    }
    uri_to_path(uri)
}

/// The URI of a document's path ([`document_path`] reversed).
pub fn document_uri(path: &Path) -> String {
    match path.to_str() {
        Some(s) if s.starts_with(UNTITLED) => s.to_owned(),
        _ => path_to_uri(path),
    }
}

/// The scheme of documents that are not files.
const UNTITLED: &str = "untitled:";

/// Whether `path` stands for an `untitled:` document ([`document_path`]).
pub fn is_untitled(path: &Path) -> bool {
    path.to_str().is_some_and(|s| s.starts_with(UNTITLED))
}

/// `file:///a%20b/c.dm` → `/a b/c.dm`.
pub fn uri_to_path(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file://")?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Some(PathBuf::from(String::from_utf8(out).ok()?))
}

/// `/a b/c.dm` → `file:///a%20b/c.dm`.
pub fn path_to_uri(path: &Path) -> String {
    let mut s = String::from("file://");
    for b in path.to_string_lossy().bytes() {
        if b.is_ascii_alphanumeric() || b"/-_.~".contains(&b) {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s
}

/// The UTF-16 position of byte `offset` in `text` (clamped to its end and
/// to a character boundary).
pub fn position_of(text: &str, offset: usize) -> Pos {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() as u32;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let character = text[line_start..offset].encode_utf16().count() as u32;
    Pos { line, character }
}

/// The byte offset of a UTF-16 position in `text` (clamped).
pub fn offset_of(text: &str, pos: Pos) -> usize {
    let mut start = 0;
    for _ in 0..pos.line {
        match text[start..].find('\n') {
            Some(i) => start += i + 1,
            None => return text.len(),
        }
    }
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let mut units = 0u32;
    for (i, c) in text[start..line_end].char_indices() {
        if units >= pos.character {
            return start + i;
        }
        units += c.len_utf16() as u32;
    }
    line_end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_round_trip() {
        let p = Path::new("/tmp/a b/ñ.dm");
        let u = path_to_uri(p);
        assert_eq!(u, "file:///tmp/a%20b/%C3%B1.dm");
        assert_eq!(uri_to_path(&u).unwrap(), p);
        assert_eq!(uri_to_path("http://x"), None);
        assert_eq!(uri_to_path("file:///bad%zz"), None);
        assert_eq!(uri_to_path("file:///cut%4"), Some(PathBuf::from("/cut%4")));
    }

    #[test]
    fn untitled_documents_round_trip() {
        let p = document_path("untitled:Untitled-1").unwrap();
        assert!(is_untitled(&p));
        assert_eq!(document_uri(&p), "untitled:Untitled-1");
        let f = document_path("file:///tmp/x.dm").unwrap();
        assert!(!is_untitled(&f));
        assert_eq!(document_uri(&f), "file:///tmp/x.dm");
    }

    #[test]
    fn positions_count_utf16() {
        let t = "ab\nñ𝄞x\n";
        let x = t.find('x').unwrap();
        assert_eq!(
            position_of(t, x),
            Pos {
                line: 1,
                character: 3
            }
        );
        assert_eq!(
            offset_of(
                t,
                Pos {
                    line: 1,
                    character: 3
                }
            ),
            x
        );
        assert_eq!(
            offset_of(
                t,
                Pos {
                    line: 9,
                    character: 0
                }
            ),
            t.len()
        );
        assert_eq!(
            position_of(t, 999),
            Pos {
                line: 2,
                character: 0
            }
        );
    }
}
