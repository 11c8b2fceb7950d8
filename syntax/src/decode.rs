//! Decoding the bytes of a text file: the one place where every reader of
//! sitlog-rs (DM and side files, KB files, scripts and typed input, Prolog
//! user functions, world files as `sitlogc` reads them) turns bytes into
//! text. (The simulator, which depends on no SitLog crate, keeps a copy of
//! these rules and messages for its own `World::load`.)
//!
//! Invariant: a file is accepted only as UTF-8 (a leading UTF-8 byte order
//! mark is skipped); anything else is a [`DecodeError`] with the 1-based line
//! and column of the first bad byte, and UTF-16 text (with a byte order mark,
//! or ASCII with every other byte zero) is named as such.

use std::borrow::Cow;

/// The UTF-8 byte order mark.
pub const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// Bytes that are not UTF-8 text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DecodeError {
    /// Byte offset of the first bad byte in the file (BOM included).
    pub offset: usize,
    /// 1-based line of the first bad byte.
    pub line: usize,
    /// 1-based column (in characters) of the first bad byte.
    pub column: usize,
    /// What is wrong, without the position (e.g. `invalid UTF-8 (byte 0xFF)`).
    pub message: String,
    /// The file is UTF-16 text.
    pub utf16: bool,
}

impl std::fmt::Display for DecodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}: {}", self.line, self.column, self.message)
    }
}

impl std::error::Error for DecodeError {}

impl DecodeError {
    /// `name:line:col: message`, for one-line errors.
    pub fn in_file(&self, name: &str) -> String {
        format!("{name}:{}:{}: {}", self.line, self.column, self.message)
    }
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
pub fn decode(bytes: &[u8]) -> Result<&str, DecodeError> {
    if let Some(kind) = utf16_kind(bytes) {
        return Err(DecodeError {
            offset: 0,
            line: 1,
            column: 1,
            message: format!("the file is {kind} text, not UTF-8: convert it to UTF-8 (e.g. with iconv -f UTF-16 -t UTF-8)"),
            utf16: true,
        });
    }
    let skip = if bytes.starts_with(UTF8_BOM) {
        UTF8_BOM.len()
    } else {
        0
    };
    let body = &bytes[skip..];
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
        DecodeError {
            offset: skip + at,
            line,
            column,
            message,
            utf16: false,
        }
    })
}

/// [`decode`] for owned bytes: no copy when they are UTF-8 without a BOM.
pub fn decode_owned(bytes: Vec<u8>) -> Result<String, DecodeError> {
    match decode(&bytes)? {
        text if text.len() == bytes.len() => {
            // Already checked: the whole vector is the text.
            Ok(String::from_utf8(bytes).unwrap_or_default())
        }
        text => Ok(text.to_owned()),
    }
}

/// The text of `bytes` with each invalid sequence replaced by U+FFFD, and
/// `offset` (a byte offset into `bytes`) moved to the same place in that
/// text; for showing a file that [`decode`] refused.
pub fn lossy_with_offset(bytes: &[u8], offset: usize) -> (Cow<'_, str>, usize) {
    let offset = offset.min(bytes.len());
    let head = String::from_utf8_lossy(&bytes[..offset]).len();
    (String::from_utf8_lossy(bytes), head)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_and_bom() {
        assert_eq!(decode(b"a.\n").unwrap(), "a.\n");
        assert_eq!(decode(b"\xEF\xBB\xBFa.").unwrap(), "a.");
        assert_eq!(decode_owned(b"\xEF\xBB\xBFa.".to_vec()).unwrap(), "a.");
        assert_eq!(decode_owned("é.".into()).unwrap(), "é.");
        assert_eq!(decode(b"").unwrap(), "");
    }

    #[test]
    fn first_bad_byte() {
        let e = decode(b"ab\nc\xC3\xA9d \xFF\xFE").unwrap_err();
        assert_eq!((e.offset, e.line, e.column), (8, 2, 5));
        assert!(e.message.contains("0xFF"), "{}", e.message);
        let e = decode(b"x.\n% caf\xC3").unwrap_err();
        assert_eq!((e.offset, e.line, e.column), (8, 2, 6));
        assert!(e.message.contains("ends inside"), "{}", e.message);
        let e = decode(b"\xEF\xBB\xBF\xFF").unwrap_err();
        assert_eq!((e.offset, e.line, e.column), (3, 1, 1));
    }

    #[test]
    fn utf16_is_named() {
        let e = decode(b"\xFF\xFEa\0.\0").unwrap_err();
        assert!(e.utf16 && e.message.contains("UTF-16 (little-endian)"));
        let e = decode(b"\0a\0b\0.").unwrap_err();
        assert!(e.message.contains("big-endian"), "{}", e.message);
        let e = decode(b"a\0b\0.\0").unwrap_err();
        assert!(e.message.contains("little-endian"), "{}", e.message);
    }

    #[test]
    fn lossy_offsets_are_char_boundaries() {
        let bytes = b"ab\xFF\xFEcd";
        let (text, at) = lossy_with_offset(bytes, 2);
        assert!(text.is_char_boundary(at));
        assert_eq!(&text[at..], "\u{FFFD}\u{FFFD}cd");
    }
}

/// The largest file a reader takes unless told otherwise (256 MiB): far
/// beyond any DM, KB, world, script or trace, small enough that reading
/// `/dev/zero` or a runaway file by mistake ends at once.
pub const DEFAULT_MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;

static MAX_FILE_BYTES: std::sync::atomic::AtomicU64 =
    std::sync::atomic::AtomicU64::new(DEFAULT_MAX_FILE_BYTES);

/// Sets the largest file [`read_file`] takes, for the whole process (the
/// command line's `--max-file-bytes`).
pub fn set_max_file_bytes(limit: u64) {
    MAX_FILE_BYTES.store(limit, std::sync::atomic::Ordering::Relaxed);
}

/// The largest file [`read_file`] takes.
pub fn max_file_bytes() -> u64 {
    MAX_FILE_BYTES.load(std::sync::atomic::Ordering::Relaxed)
}

/// Reads the bytes of the file at `path`, at most [`max_file_bytes`]: a
/// longer file (or an endless one such as `/dev/zero`) is an error saying
/// the limit and its option, after reading no more than the limit and one
/// byte. Every reader of a file of a program or a run goes through here.
pub fn read_file(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let limit = max_file_bytes();
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than the limit of {limit} bytes (option --max-file-bytes)"),
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod read_file_tests {
    #[test]
    fn an_endless_file_is_refused_at_the_limit() {
        super::set_max_file_bytes(1000);
        let e = super::read_file(std::path::Path::new("/dev/zero")).unwrap_err();
        super::set_max_file_bytes(super::DEFAULT_MAX_FILE_BYTES);
        assert!(e.to_string().contains("limit of 1000 bytes"), "{e}");
    }
}
