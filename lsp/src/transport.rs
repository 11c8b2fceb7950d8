//! The stdio transport of the language server: JSON-RPC messages framed by
//! `Content-Length` headers, read on one thread and written on another.
//!
//! Invariant: no more than the message limit is ever allocated for one
//! message, whatever its header says: a `Content-Length` over the limit ends
//! the session with an error naming the length, the limit and its option,
//! before a byte of the body is read; the body is read as it arrives.

use crossbeam_channel::{bounded, Receiver, Sender};
use lsp_server::Message;
use std::io::{self, BufRead, Read, Write};
use std::thread::JoinHandle;

/// The largest message the server reads by default (64 MiB): far beyond
/// any DM an editor sends; `sitlogc lsp --max-message-bytes` raises it.
pub const DEFAULT_MAX_MESSAGE_BYTES: u64 = 64 * 1024 * 1024;

/// The longest header line read (bytes).
const MAX_HEADER_LINE: u64 = 8 * 1024;

/// Reads one message from `input`: `Ok(None)` at end of input before a
/// header. Errors name what was wrong with the frame.
pub fn read_message(input: &mut impl BufRead, limit: u64) -> io::Result<Option<Message>> {
    let mut size: Option<u64> = None;
    let mut first = true;
    loop {
        let mut line = Vec::new();
        let n = input
            .by_ref()
            .take(MAX_HEADER_LINE + 1)
            .read_until(b'\n', &mut line)?;
        if n == 0 {
            if first {
                return Ok(None);
            }
            return Err(invalid("end of input inside a message header"));
        }
        first = false;
        if line.len() as u64 > MAX_HEADER_LINE {
            return Err(invalid(&format!(
                "a header line longer than {MAX_HEADER_LINE} bytes"
            )));
        }
        let line = String::from_utf8(line).map_err(|_| invalid("a header that is not UTF-8"))?;
        let line = line.trim_end_matches(['\r', '\n']);
        if line.is_empty() {
            break;
        }
        let Some((name, value)) = line.split_once(": ") else {
            return Err(invalid(&format!("malformed header {line:?}")));
        };
        if name.eq_ignore_ascii_case("Content-Length") {
            let n: u64 = value
                .trim()
                .parse()
                .map_err(|_| invalid(&format!("Content-Length {value:?} is not a number")))?;
            if n > limit {
                return Err(invalid(&format!(
                    "a message of {n} bytes (Content-Length) is over the limit of {limit} bytes (option --max-message-bytes)"
                )));
            }
            size = Some(n);
        }
    }
    let size = size.ok_or_else(|| invalid("a message without Content-Length"))?;
    // read as the bytes arrive: nothing is reserved from the header alone
    let mut body = Vec::new();
    let got = input.by_ref().take(size).read_to_end(&mut body)?;
    if (got as u64) < size {
        return Err(invalid(&format!(
            "end of input after {got} of the {size} bytes of a message"
        )));
    }
    serde_json::from_slice(&body)
        .map(Some)
        .map_err(|e| invalid(&format!("a message that is not JSON-RPC: {e}")))
}

fn invalid(message: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message.to_owned())
}

/// The threads of a stdio connection.
pub struct Threads {
    reader: JoinHandle<io::Result<()>>,
    writer: JoinHandle<io::Result<()>>,
}

impl Threads {
    /// Waits for both threads: the reader's error first.
    pub fn join(self) -> io::Result<()> {
        let reader = self
            .reader
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("the reader thread failed")));
        let writer = self
            .writer
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("the writer thread failed")));
        reader.and(writer)
    }
}

/// A connection over stdin/stdout reading messages of at most `limit`
/// bytes.
pub fn stdio(limit: u64) -> io::Result<(lsp_server::Connection, Threads)> {
    let (to_writer, from_server): (Sender<Message>, Receiver<Message>) = bounded(0);
    let writer = std::thread::Builder::new()
        .name("sitlog-lsp-writer".to_owned())
        .spawn(move || {
            let stdout = io::stdout();
            let mut out = stdout.lock();
            for msg in from_server {
                msg.write(&mut out)?;
                out.flush()?;
            }
            Ok(())
        })?;
    let (to_server, from_reader) = bounded::<Message>(0);
    let reader = std::thread::Builder::new()
        .name("sitlog-lsp-reader".to_owned())
        .spawn(move || {
            let stdin = io::stdin();
            let mut input = stdin.lock();
            while let Some(msg) = read_message(&mut input, limit)? {
                let exit = matches!(&msg, Message::Notification(n) if n.method == "exit");
                if to_server.send(msg).is_err() || exit {
                    break;
                }
            }
            Ok(())
        })?;
    Ok((
        lsp_server::Connection {
            sender: to_writer,
            receiver: from_reader,
        },
        Threads { reader, writer },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(bytes: &[u8], limit: u64) -> io::Result<Option<Message>> {
        read_message(&mut io::Cursor::new(bytes), limit)
    }

    #[test]
    fn a_message_is_read() {
        let body = r#"{"jsonrpc":"2.0","method":"exit"}"#;
        let text = format!("Content-Length: {}\r\n\r\n{body}", body.len());
        let msg = read(text.as_bytes(), 1000).unwrap().unwrap();
        assert!(matches!(msg, Message::Notification(n) if n.method == "exit"));
        assert!(read(b"", 1000).unwrap().is_none());
    }

    #[test]
    fn a_length_over_the_limit_is_refused_before_the_body() {
        let e = read(b"Content-Length: 1000000000000\r\n\r\n", 1000).unwrap_err();
        assert!(e.to_string().contains("1000000000000 bytes"), "{e}");
        assert!(e.to_string().contains("--max-message-bytes"), "{e}");
    }

    #[test]
    fn bad_frames_are_errors() {
        for bad in [
            &b"Content-Length: x\r\n\r\n"[..],
            b"Content-Length: 10\r\n\r\n{}",
            b"Content-Length: 2\r\n\r\nxx",
            b"\r\n{}",
            b"Content-Length: 2\r\n",
        ] {
            assert!(read(bad, 1000).is_err(), "{bad:?}");
        }
        let long = vec![b'a'; 20_000];
        assert!(read(&long, 1000).is_err());
    }
}
