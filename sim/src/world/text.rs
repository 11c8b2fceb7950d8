//! The bytes of a world file as text. Invariant: a file is accepted only as
//! UTF-8 (a leading UTF-8 byte order mark is skipped); anything else is an
//! error at the 1-based line and column of the first bad byte, and UTF-16
//! text (with a byte order mark, or ASCII with every other byte zero) is
//! named as such.
//!
//! These are the rules and the messages of the toolchain's other readers
//! (`sitlog_syntax::decode`), kept here as a copy so that the simulator
//! depends on nothing of SitLog: a world file read by [`crate::World::load`]
//! and one read by the robot's front end give the same error, word for word.

/// The UTF-8 byte order mark.
const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// Bytes that are not UTF-8 text: where the first bad byte is and what is
/// wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct NotText {
    /// 1-based line of the first bad byte.
    pub line: usize,
    /// 1-based column (in characters) of the first bad byte.
    pub column: usize,
    /// What is wrong, without the position.
    pub message: String,
}

/// Whether `bytes` look like UTF-16 text: a UTF-16 byte order mark, or at
/// least two ASCII characters of which every one has a zero byte beside it.
fn utf16_kind(bytes: &[u8]) -> Option<&'static str> {
    match bytes {
        [0xFF, 0xFE, ..] => return Some("UTF-16 (little-endian)"),
        [0xFE, 0xFF, ..] => return Some("UTF-16 (big-endian)"),
        _ => {}
    }
    let pairs: Vec<&[u8]> = bytes.chunks_exact(2).take(64).collect();
    if pairs.len() < 2 {
        return None;
    }
    if pairs.iter().all(|p| p[1] == 0 && p[0] != 0 && p[0] < 0x80) {
        return Some("UTF-16 (little-endian)");
    }
    if pairs.iter().all(|p| p[0] == 0 && p[1] != 0 && p[1] < 0x80) {
        return Some("UTF-16 (big-endian)");
    }
    None
}

/// The text of a file: its bytes without a leading UTF-8 BOM, if they are
/// UTF-8; else an error at the first bad byte.
pub(super) fn decode(bytes: &[u8]) -> Result<&str, NotText> {
    if let Some(kind) = utf16_kind(bytes) {
        return Err(NotText {
            line: 1,
            column: 1,
            message: format!("the file is {kind} text, not UTF-8: convert it to UTF-8 (e.g. with iconv -f UTF-16 -t UTF-8)"),
        });
    }
    let body = bytes.strip_prefix(UTF8_BOM).unwrap_or(bytes);
    std::str::from_utf8(body).map_err(|e| {
        let at = e.valid_up_to();
        // The prefix is UTF-8 by definition.
        let good = std::str::from_utf8(&body[..at]).unwrap_or("");
        let line_start = good.rfind('\n').map_or(0, |i| i + 1);
        let line = 1 + good.bytes().filter(|&b| b == b'\n').count();
        let column = 1 + good[line_start..].chars().count();
        let message = match e.error_len() {
            Some(_) => format!(
                "invalid UTF-8 (byte 0x{:02X}): the file must be UTF-8 text",
                body[at]
            ),
            None => format!(
                "the file ends inside a UTF-8 character (byte 0x{:02X}): it is truncated or not UTF-8",
                body[at]
            ),
        };
        NotText {
            line,
            column,
            message,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_and_bom() {
        assert_eq!(decode(b"a = 1\n").unwrap(), "a = 1\n");
        assert_eq!(decode(b"\xEF\xBB\xBFa = 1").unwrap(), "a = 1");
        assert_eq!(decode(b"").unwrap(), "");
    }

    #[test]
    fn first_bad_byte() {
        let e = decode(b"ab\nc\xC3\xA9d \xFF\xFE").unwrap_err();
        assert_eq!((e.line, e.column), (2, 5));
        assert!(e.message.contains("0xFF"), "{}", e.message);
        let e = decode(b"x.\n# caf\xC3").unwrap_err();
        assert_eq!((e.line, e.column), (2, 6));
        assert!(e.message.contains("ends inside"), "{}", e.message);
        let e = decode(b"\xEF\xBB\xBF\xFF").unwrap_err();
        assert_eq!((e.line, e.column), (1, 1));
    }

    #[test]
    fn utf16_is_named() {
        let e = decode(b"\xFF\xFEa\0.\0").unwrap_err();
        assert!(
            e.message.contains("UTF-16 (little-endian)"),
            "{}",
            e.message
        );
        let e = decode(b"\0a\0b\0.").unwrap_err();
        assert!(e.message.contains("big-endian"), "{}", e.message);
    }
}
