//! Reading a KB file and writing it back: the text format (kb.md section 1,
//! final `.` optional, saved in `writeq` form) and atomic replacement of the
//! file (temporary file in the same directory, fsync, rename, fsync of the
//! directory), so a crash never leaves a half-written KB.
//!
//! A process that persists a KB holds [`PersistLock`]: an exclusive lock
//! (fs4) on the file `.NAME.lock` beside the KB, so a second persisting
//! process is refused instead of silently overwriting the first one's
//! updates. Taking the lock removes the temporary files (`.NAME.PID.XXXXXX.tmp`)
//! that a killed run left behind; the lock file itself stays (one empty
//! file per KB, reused by every run). A KB file with more than one hard
//! link is refused (when locked and at each save): replacing it would
//! split the link, and its names would have two locks.

use crate::entry::ARROW;
use crate::model::{Kb, ModelError};
use crate::store::Built;
use sitlog_syntax::{atoms, line_col, Atom, Clause};
use std::fmt;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// A KB that could not be loaded: `PATH:LINE:COL: error: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    pub path: String,
    /// 1-based line and column (characters); `None` for I/O errors.
    pub pos: Option<(usize, usize)>,
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.pos {
            Some((l, c)) => write!(f, "{}:{}:{}: error: {}", self.path, l, c, self.message),
            None => write!(f, "{}: error: {}", self.path, self.message),
        }
    }
}

impl std::error::Error for LoadError {}

/// The right to persist one KB file, held for as long as this value lives
/// (the operating system releases it when the process ends, however).
#[derive(Debug)]
pub struct PersistLock {
    path: PathBuf,
    _file: std::fs::File,
}

impl PersistLock {
    /// The KB file this lock is for.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// `dir` and file name of `path` (`.` for a bare file name).
fn dir_and_name(path: &Path) -> (PathBuf, String) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_owned(),
        _ => PathBuf::from("."),
    };
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "kb".to_owned());
    (dir, file_name)
}

/// The file `path` names, following symbolic links (as many as the system
/// allows, relative ones from their own directory); a dangling link gives
/// the path it points to, so that saving creates the target, not a file in
/// place of the link.
pub fn real_path(path: &Path) -> PathBuf {
    let mut path = path.to_owned();
    for _ in 0..40 {
        match std::fs::read_link(&path) {
            Ok(target) => {
                path = match path.parent() {
                    Some(dir) if target.is_relative() => dir.join(target),
                    _ => target,
                };
            }
            Err(_) => break,
        }
    }
    path
}

/// Takes the persistence lock of the KB file `path` without waiting, then
/// removes the temporary files that killed runs left beside it. Another
/// process holding the lock is an error naming it.
///
/// `path` is resolved once, here ([`real_path`]): the lock, the temporary
/// files and every save are beside and of the real file, so a symbolic link
/// stays a link, its target is what changes, and a run persisting the target
/// by another name is excluded too. A path that is not a regular file (a
/// device, a FIFO, a directory) is refused.
pub fn lock_for_persist(path: &Path) -> Result<PersistLock, LoadError> {
    let shown = path.display().to_string();
    let err = |message: String| LoadError {
        path: shown.clone(),
        pos: None,
        message,
    };
    let path = &real_path(path);
    if let Ok(m) = std::fs::metadata(path) {
        if !m.is_file() {
            return Err(err(format!(
                "{} is not a regular file: a KB to persist must be one",
                path.display()
            )));
        }
    }
    if let Some(message) = hard_linked(path) {
        return Err(err(message));
    }
    let (dir, name) = dir_and_name(path);
    let lock_path = dir.join(format!(".{name}.lock"));
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .map_err(|e| {
            err(format!(
                "cannot open the lock file {}: {e}",
                lock_path.display()
            ))
        })?;
    match fs4::FileExt::try_lock(&file) {
        Ok(()) => {}
        Err(fs4::TryLockError::WouldBlock) => {
            return Err(err(format!(
                "another process is persisting this KB (it holds {}); two persisting runs would overwrite each other's updates",
                lock_path.display()
            )))
        }
        Err(fs4::TryLockError::Error(e)) => {
            return Err(err(format!("cannot lock {}: {e}", lock_path.display())))
        }
    }
    remove_stale_temporaries(&dir, &name);
    Ok(PersistLock {
        path: path.to_owned(),
        _file: file,
    })
}

/// Why `path` (a real file) cannot be persisted when it has more than one
/// hard link, `None` otherwise. A save replaces the file (a new one renamed
/// over it, so that a crash never leaves half a KB): the other names would
/// keep the old file, the link split; and two runs persisting the file
/// under two names would take two different locks. So a hard-linked KB is
/// refused, by both runs, and never written (a symbolic link is followed
/// instead: it stays a link).
fn hard_linked(path: &Path) -> Option<String> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let links = std::fs::metadata(path).ok()?.nlink();
        (links > 1).then(|| {
            format!(
                "{} has {links} hard links: persisting replaces the file (a new one renamed over it), which would split them, and two runs persisting it under two names would not exclude each other; persist a copy, or point the other names at it with symbolic links",
                path.display()
            )
        })
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

/// Removes `.NAME.PID.XXXXXX.tmp` (and the older `.NAME.PID.tmp`) in `dir`
/// (only called under the lock: no other process is writing one).
fn remove_stale_temporaries(dir: &Path, name: &str) {
    let prefix = format!(".{name}.");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let file = file.to_string_lossy();
        if let Some(middle) = file
            .strip_prefix(&prefix)
            .and_then(|r| r.strip_suffix(".tmp"))
        {
            // `PID.XXXXXX` (tempfile's random part), or `PID` (older runs).
            let (pid, random) = middle.split_once('.').unwrap_or((middle, ""));
            if !pid.is_empty()
                && pid.bytes().all(|b| b.is_ascii_digit())
                && random.bytes().all(|b| b.is_ascii_alphanumeric())
            {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }
}

impl Kb {
    /// Locks `path` for persistence ([`lock_for_persist`]) and loads it;
    /// save to [`PersistLock::path`], the real file.
    pub fn open_persistent(path: &Path) -> Result<(Kb, PersistLock), LoadError> {
        let lock = lock_for_persist(path)?;
        let kb = Kb::load(lock.path())?;
        Ok((kb, lock))
    }
}

/// Saving failed (the old file is left as it was).
#[derive(Debug)]
pub struct PersistError {
    pub path: PathBuf,
    pub error: std::io::Error,
}

impl fmt::Display for PersistError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: error: cannot save the KB: {}",
            self.path.display(),
            self.error
        )
    }
}

impl std::error::Error for PersistError {}

impl Kb {
    /// Parses and validates KB text; `name` labels errors (a path).
    pub fn parse(src: &str, name: &str) -> Result<Kb, LoadError> {
        let at = |span_start: u32, message: String| LoadError {
            path: name.to_owned(),
            pos: Some(line_col(src, span_start as usize)),
            message,
        };
        let clause: Clause =
            sitlog_syntax::read_term(src).map_err(|e| at(e.span.start, e.message.clone()))?;
        Kb::from_clause(&clause).map_err(|ModelError { span, message }| at(span.start, message))
    }

    /// Parses the bytes of a KB file: text that is not UTF-8 is an error at
    /// the line and column of the first bad byte (a UTF-8 BOM is skipped).
    pub fn parse_bytes(bytes: &[u8], name: &str) -> Result<Kb, LoadError> {
        let src = sitlog_syntax::decode(bytes).map_err(|e| LoadError {
            path: name.to_owned(),
            pos: Some((e.line, e.column)),
            message: e.message,
        })?;
        Kb::parse(src, name)
    }

    /// Loads a KB file.
    pub fn load(path: &Path) -> Result<Kb, LoadError> {
        let name = path.display().to_string();
        let bytes = sitlog_syntax::read_file(path).map_err(|e| LoadError {
            path: name.clone(),
            pos: None,
            message: format!("cannot read the KB: {e}"),
        })?;
        Kb::parse_bytes(&bytes, &name)
    }

    /// Replaces this KB by the one in `path`; on error this KB is unchanged.
    pub fn reload(&mut self, path: &Path) -> Result<(), LoadError> {
        *self = Kb::load(path)?;
        Ok(())
    }

    /// The KB in the file format: the list in `writeq` form, one class a line.
    pub fn to_text(&self) -> String {
        let mut out = String::from("[");
        let class_atom = Atom::intern("class");
        for (n, cl) in self.classes.iter().enumerate() {
            let mut b = Built::new(&self.store);
            let props: Vec<_> = cl.props.iter().map(|e| e.pair).collect();
            let rels: Vec<_> = cl.rels.iter().map(|e| e.pair).collect();
            let props = b.list(&props);
            let rels = b.list(&rels);
            let mut inds = Vec::with_capacity(cl.inds.len());
            for &i in &cl.inds {
                let ind = &self.inds[i as usize];
                let id = b.atom(atoms::ID);
                let head = b.compound(ARROW, &[id, ind.id]);
                let p: Vec<_> = ind.props.iter().map(|e| e.pair).collect();
                let r: Vec<_> = ind.rels.iter().map(|e| e.pair).collect();
                let p = b.list(&p);
                let r = b.list(&r);
                inds.push(b.list(&[head, p, r]));
            }
            let inds = b.list(&inds);
            let t = b.compound(class_atom, &[cl.id, cl.mother, props, rels, inds]);
            if n > 0 {
                out.push_str(",\n");
            }
            out.push_str(&b.writeq(t));
        }
        out.push_str("]\n");
        out
    }

    /// Saves atomically: the file holds either the old or the new KB.
    pub fn save(&self, path: &Path) -> Result<(), PersistError> {
        write_atomic(path, self.to_text().as_bytes()).map_err(|error| PersistError {
            path: path.to_owned(),
            error,
        })
    }

    /// Applies an update and persists the result; the KB in memory and on
    /// disk change together or not at all.
    pub fn update_persist(
        &mut self,
        update: &Clause,
        path: &Path,
    ) -> Result<Result<bool, crate::CallError>, PersistError> {
        let mut next = self.clone();
        match next.update(update) {
            Ok(true) => {
                next.save(path)?;
                *self = next;
                Ok(Ok(true))
            }
            other => Ok(other),
        }
    }
}

/// Writes `data` to a temporary file beside the real file of `path`
/// ([`real_path`]: a symbolic link stays a link) (tempfile: removed whatever
/// goes wrong before the rename), syncs it, keeps the old file's permissions
/// when it is a regular file, renames it over the real file and syncs the
/// directory.
fn write_atomic(path: &Path, data: &[u8]) -> std::io::Result<()> {
    let path = &real_path(path);
    // A hard link made while the run persists: refused, not split.
    if let Some(message) = hard_linked(path) {
        return Err(std::io::Error::other(message));
    }
    let (dir, file_name) = dir_and_name(path);
    // `.NAME.PID.XXXXXX.tmp`: what `remove_stale_temporaries` recognises.
    let mut tmp = tempfile::Builder::new()
        .prefix(&format!(".{file_name}.{}.", std::process::id()))
        .suffix(".tmp")
        .tempfile_in(&dir)?;
    tmp.as_file_mut().write_all(data)?;
    match std::fs::symlink_metadata(path) {
        Ok(old) if old.is_file() => tmp.as_file().set_permissions(old.permissions())?,
        // A new KB file (or something that is not a file, whose mode says
        // nothing about a KB's): readable by others, as `File::create` makes
        // it (tempfile makes its files private).
        #[cfg(unix)]
        _ => {
            use std::os::unix::fs::PermissionsExt;
            tmp.as_file()
                .set_permissions(std::fs::Permissions::from_mode(0o644))?
        }
        #[cfg(not(unix))]
        _ => {}
    }
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    // Make the rename itself durable; not every platform can open a directory.
    if let Ok(d) = std::fs::File::open(&dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

#[cfg(test)]
mod lock_tests {
    use super::*;

    #[test]
    fn the_lock_refuses_a_second_holder_and_removes_stale_temporaries() {
        let dir = std::env::temp_dir().join(format!("sitlog-kb-lock-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let kb = dir.join("k.kb");
        std::fs::write(&kb, "[class(top,none,[],[],[])].\n").unwrap();
        std::fs::write(dir.join(".k.kb.123.tmp"), "half").unwrap();
        std::fs::write(dir.join(".k.kb.456.a1B2c3.tmp"), "half").unwrap();
        std::fs::write(dir.join(".k.kb.notes.tmp"), "not ours").unwrap();
        let (_, lock) = Kb::open_persistent(&kb).unwrap();
        assert!(!dir.join(".k.kb.123.tmp").exists());
        assert!(!dir.join(".k.kb.456.a1B2c3.tmp").exists());
        assert!(dir.join(".k.kb.notes.tmp").exists());
        let e = lock_for_persist(&kb).unwrap_err();
        assert!(e.message.contains("another process"), "{e}");
        drop(lock);
        assert!(lock_for_persist(&kb).is_ok());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Issue 38: a hard-linked KB is refused under both names, and a link
    /// made while a run persists is refused at the next save; the link is
    /// never split.
    #[cfg(unix)]
    #[test]
    fn a_hard_linked_kb_is_refused_and_never_split() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().unwrap();
        let kb = dir.path().join("k.kb");
        let other = dir.path().join("other.kb");
        std::fs::write(&kb, "[class(top,none,[],[],[])].\n").unwrap();
        let (mut loaded, lock) = Kb::open_persistent(&kb).unwrap();
        std::fs::hard_link(&kb, &other).unwrap();
        for name in [&kb, &other] {
            let e = lock_for_persist(name).unwrap_err();
            assert!(e.message.contains("has 2 hard links"), "{e}");
        }
        let update = sitlog_syntax::read_term("add_class(b, top)").unwrap();
        let e = loaded.update_persist(&update, lock.path()).unwrap_err();
        assert!(e.to_string().contains("has 2 hard links"), "{e}");
        let (a, b) = (
            std::fs::metadata(&kb).unwrap(),
            std::fs::metadata(&other).unwrap(),
        );
        assert_eq!((a.ino(), a.nlink()), (b.ino(), 2));
    }
}
