//! The KB-reach analysis once per tree (`--legacy-kb native`): its result
//! ([`Reach`]) kept in a file of the cache directory, named by a hash of
//! the analysis' whole input (every clause and directive as the analysis
//! sees it: a head's variables, not its atoms, which it never looks at;
//! the served predicates) and of this build's analysis code, so the tasks
//! of one application, which read the same layer and the same files,
//! analyse them once (wherever the tree is: the `getenv` fact naming it
//! is a head).
//!
//! Invariant: a cached result is used only for the very input it was
//! computed from. The file repeats the 128-bit key in its first line and
//! ends with a count of its entries and a 64-bit checksum of the text
//! before that line; a file whose key, syntax, count or checksum does not
//! match (stale, corrupt, truncated, edited, written by another build) is
//! ignored and the analysis runs as without a cache (then rewrites it).
//! A cache that cannot be written is no error: the run goes on.

use super::kb_reach::{self, Clause, Program, Reach, Served, T};
use sitlog_syntax::Atom;
use std::hash::Hasher;
use std::path::{Path, PathBuf};

/// The first word of a cache file (its format's version).
const MAGIC: &str = "sitlog-kb-reach-1";

/// The environment variable that chooses the cache directory (as for
/// `sitlogc build`'s cache).
const CACHE_ENV: &str = "SITLOGC_CACHE_DIR";

/// The directory of the analysis' cache files: `$SITLOGC_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/sitlogc`, else `~/.cache/sitlogc` (absolute paths
/// only), under `kb_reach`; `None` without one.
pub fn default_dir() -> Option<PathBuf> {
    let var = |name: &str| {
        std::env::var_os(name)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
    };
    let base = var(CACHE_ENV)
        .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("sitlogc")))
        .or_else(|| var("HOME").map(|d| d.join(".cache").join("sitlogc")))?;
    Some(base.join("kb_reach"))
}

/// The analysis of `program`, read from `dir` if it was done before on the
/// same input, else done (and written there).
pub(super) fn analyse(program: &Program<'_>, dir: Option<&Path>) -> Reach {
    let Some(dir) = dir else {
        return kb_reach::analyse(program);
    };
    let key = key(program);
    let path = dir.join(format!("{key}.txt"));
    if let Some(reach) = std::fs::read_to_string(&path)
        .ok()
        .and_then(|text| read(&text, &key))
    {
        return reach;
    }
    let reach = kb_reach::analyse(program);
    write(dir, &path, &key, &reach);
    reach
}

/// 128 bits (two SipHashes) of the analysis' input and of its code: the
/// input written out as bytes first, then hashed at once (cheaper than a
/// hasher call per part).
fn key(program: &Program<'_>) -> String {
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 20);
    put_str(&mut buf, MAGIC);
    // The analysis' code: another build's result is not this one's.
    put_str(&mut buf, include_str!("kb_reach.rs"));
    put_str(&mut buf, include_str!("reach_cache.rs"));
    put_served(&mut buf, program.served);
    put_num(&mut buf, program.clauses.len());
    for c in program.clauses {
        put_clause(&mut buf, c);
    }
    let mut a = std::collections::hash_map::DefaultHasher::new();
    let mut b = std::collections::hash_map::DefaultHasher::new();
    b.write_u8(0x5a);
    a.write(&buf);
    b.write(&buf);
    format!("{:016x}{:016x}", a.finish(), b.finish())
}

fn put_num(buf: &mut Vec<u8>, n: usize) {
    buf.extend_from_slice(&(n as u64).to_le_bytes());
}

fn put_str(buf: &mut Vec<u8>, s: &str) {
    put_num(buf, s.len());
    buf.extend_from_slice(s.as_bytes());
}

fn put_served(buf: &mut Vec<u8>, s: &Served) {
    for set in [&s.queries, &s.updates, &s.loads, &s.saves] {
        let mut v: Vec<(&str, usize)> = set.iter().map(|(a, n)| (a.as_str(), *n)).collect();
        v.sort_unstable();
        put_num(buf, v.len());
        for (a, n) in v {
            put_str(buf, a);
            put_num(buf, n);
        }
    }
}

fn put_clause(buf: &mut Vec<u8>, c: &Clause) {
    match c.key {
        Some((a, n)) => {
            buf.push(1);
            put_str(buf, a.as_str());
            put_num(buf, n);
        }
        None => buf.push(0),
    }
    put_num(buf, c.vars);
    // Of a head, the analysis looks only at each argument's variables (its
    // atoms, a fact's file names say, are no part of the input).
    put_num(buf, c.head.len());
    for t in &c.head {
        let vs = t.all_vars();
        put_num(buf, vs.len());
        for v in vs {
            buf.extend_from_slice(&v.to_le_bytes());
        }
    }
    match &c.body {
        Some(b) => {
            buf.push(1);
            put_t(buf, b);
        }
        None => buf.push(0),
    }
}

fn put_t(buf: &mut Vec<u8>, t: &T) {
    match t {
        T::Var(v) => {
            buf.push(0);
            buf.extend_from_slice(&v.to_le_bytes());
        }
        T::Atom(a) => {
            buf.push(1);
            put_str(buf, a.as_str());
        }
        T::Other => buf.push(2),
        T::Comp(f, args) => {
            buf.push(3);
            put_str(buf, f.as_str());
            put_num(buf, args.len());
            for a in args {
                put_t(buf, a);
            }
        }
        T::Vars(vs) => {
            buf.push(4);
            put_num(buf, vs.len());
            for v in vs {
                buf.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
}

/// The file's text: `MAGIC KEY`, `top 0|1`, then one line per entry
/// (`p`, `i`: position; `u`: predicate), a name written as its length in
/// bytes, `:`, the name; then `end COUNT SUM`, `SUM` the checksum of all
/// that comes before it.
fn text(key: &str, reach: &Reach) -> String {
    let mut out = format!("{MAGIC} {key}\ntop {}\n", u8::from(reach.top));
    let mut lines: Vec<String> = Vec::new();
    let name = |a: Atom| format!("{}:{}", a.as_str().len(), a.as_str());
    for (tag, set) in [("p", &reach.positions), ("i", &reach.inputs)] {
        for &(a, n, i) in set {
            lines.push(format!("{tag} {} {n} {i}", name(a)));
        }
    }
    for &(a, n) in &reach.undefined {
        lines.push(format!("u {} {n}", name(a)));
    }
    lines.sort_unstable();
    for l in &lines {
        out.push_str(l);
        out.push('\n');
    }
    let sum = checksum(&out);
    out.push_str(&format!("end {} {sum:016x}\n", lines.len()));
    out
}

/// A file's checksum: a SipHash of its text before the `end` line.
fn checksum(body: &str) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    h.write(body.as_bytes());
    h.finish()
}

/// The result a cache file holds for `key`; `None` for anything else.
fn read(text: &str, key: &str) -> Option<Reach> {
    let mut rest = text;
    let line = |rest: &mut &str| -> Option<String> {
        let (l, r) = rest.split_once('\n')?;
        *rest = r;
        Some(l.to_owned())
    };
    if line(&mut rest)? != format!("{MAGIC} {key}") {
        return None;
    }
    let mut reach = Reach {
        top: match line(&mut rest)?.as_str() {
            "top 0" => false,
            "top 1" => true,
            _ => return None,
        },
        ..Default::default()
    };
    let mut count = 0usize;
    loop {
        let body = &text[..text.len() - rest.len()];
        let tag = rest.get(..2)?;
        rest = &rest[2..];
        if tag == "en" {
            let l = line(&mut rest)?;
            let (n, sum) = l.strip_prefix("d ")?.split_once(' ')?;
            let n: usize = n.parse().ok()?;
            let sum = u64::from_str_radix(sum, 16).ok()?;
            let whole = n == count && rest.is_empty() && sum == checksum(body);
            return whole.then_some(reach);
        }
        // A name: its length, `:`, its bytes.
        let (len, r) = rest.split_once(':')?;
        let len: usize = len.parse().ok()?;
        let name = Atom::intern(r.get(..len)?);
        rest = &r[len..];
        let nums: Vec<usize> = line(&mut rest)?
            .split(' ')
            .skip(1)
            .map(|n| n.parse().ok())
            .collect::<Option<_>>()?;
        match (tag, nums.as_slice()) {
            ("p ", &[n, i]) if i < n => reach.positions.insert((name, n, i)),
            ("i ", &[n, i]) if i < n => reach.inputs.insert((name, n, i)),
            ("u ", &[n]) => reach.undefined.insert((name, n)),
            _ => return None,
        };
        count += 1;
    }
}

/// Writes the file atomically (a temporary file renamed); errors ignored.
fn write(dir: &Path, path: &Path, key: &str, reach: &Reach) {
    if std::fs::create_dir_all(dir).is_err() {
        return;
    }
    let tmp = dir.join(format!(".{key}.{}.tmp", std::process::id()));
    if std::fs::write(&tmp, text(key, reach)).is_ok() && std::fs::rename(&tmp, path).is_ok() {
        return;
    }
    let _ = std::fs::remove_file(&tmp);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Reach {
        let mut r = Reach::default();
        r.positions.insert((Atom::intern("a b\n:c"), 3, 2));
        r.positions.insert((Atom::intern("q"), 1, 0));
        r.inputs.insert((Atom::intern("q"), 1, 0));
        r.undefined.insert((Atom::intern("'x'"), 2));
        r
    }

    fn same(a: &Reach, b: &Reach) -> bool {
        a.top == b.top
            && a.positions == b.positions
            && a.inputs == b.inputs
            && a.undefined == b.undefined
    }

    #[test]
    fn a_cache_file_reads_back_only_for_its_key_and_whole() {
        let r = sample();
        let t = text("k1", &r);
        assert!(same(&read(&t, "k1").unwrap(), &r));
        // Another key (a stale file), a truncated or altered file: ignored.
        assert!(read(&t, "k2").is_none());
        for cut in 0..t.len() {
            assert!(read(&t[..cut], "k1").is_none(), "cut at {cut}");
        }
        assert!(read(&t.replace("end 4", "end 3"), "k1").is_none());
        // An edit that keeps the syntax and the count: the checksum.
        assert!(read(&t.replace("1:q 1 0", "1:r 1 0"), "k1").is_none());
        assert!(read(&t.replace("q 1 0", "q 1 1"), "k1").is_none());
        assert!(read(&t.replace("top 0", "top 2"), "k1").is_none());
        assert!(read(&format!("{t}p 1:q 1 0\n"), "k1").is_none());
    }

    #[test]
    fn the_analysis_is_read_from_the_cache_for_the_same_input_only() {
        let dir = std::env::temp_dir().join(format!("sitlog-reach-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let served = Served::default();
        let clause = |name: &str| Clause {
            key: Some((Atom::intern(name), 1)),
            head: vec![T::Var(0)],
            body: None,
            vars: 1,
        };
        let one = [clause("p")];
        let program = Program {
            clauses: &one,
            served: &served,
        };
        let k = key(&program);
        assert!(!same(&analyse(&program, Some(&dir)), &sample()));
        let path = dir.join(format!("{k}.txt"));
        assert!(path.exists());
        // What the file says is used for that input...
        std::fs::write(&path, text(&k, &sample())).unwrap();
        assert!(same(&analyse(&program, Some(&dir)), &sample()));
        // ...a corrupt file is not, and is replaced.
        std::fs::write(&path, "garbage").unwrap();
        assert!(!same(&analyse(&program, Some(&dir)), &sample()));
        assert!(read(&std::fs::read_to_string(&path).unwrap(), &k).is_some());
        // Another input has another key.
        let two = [clause("p"), clause("q")];
        let other = Program {
            clauses: &two,
            served: &served,
        };
        assert_ne!(key(&other), k);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
