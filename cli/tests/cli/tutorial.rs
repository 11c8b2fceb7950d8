//! The tutorial (`docs/guide/tutorial.md`) is what `sitlogc` does: every
//! fenced block of the page is checked against the files and a real run of
//! the `sitlogc` under test, so the page cannot drift (issue 30). The same
//! markers check the examples of `docs/guide/language.md` that have one.
//!
//! - A `console` block is a terminal session: each `$ sitlogc ARGS` line is
//!   run (in a scratch directory holding a copy of `dms/examples/tutorial`,
//!   with `HOME` there; `> FILE` at its end puts stdout into FILE) and the
//!   lines after it are its stderr then its stdout. A `|: TEXT` line is the
//!   prompt with what the user typed: TEXT is given on stdin. `$ mkdir DIR`
//!   is done; any other `$` line is not run and shows nothing.
//! - An `sh` block holds commands (what they print is in other blocks).
//!   Every `sh` and `console` block of README.md and of every guide page
//!   is run by [`every_command_block_of_the_readme_and_the_guide_is_run_or_says_why_not`]
//!   (issue 40), or says why not: its marker holds `run` (each `sitlogc` or
//!   `mkdir` line is run in a scratch directory with links to the
//!   repository's `dms`, `kb`, `tests` and `benches`, and must succeed;
//!   `sitlogc ... | diff FILE -` compares stdout with FILE; `# ...` is a
//!   comment) or `skip: REASON` (ROS 2, a release build, a browser, a
//!   synopsis with placeholders, ...).
//! - Any other block (`text`, `json`, `prolog`, ...) has a marker right
//!   before it, `<!-- test` ... `-->`, one instruction per line:
//!   `$ sitlogc ARGS` runs a command (as in a console block); `write FILE:
//!   TEXT` and `replace FILE: OLD` with a line `by: NEW` after it (both
//!   with `\n` for a line break; `write FILE: (the block above)` writes the
//!   text of the block before this one) prepare files;
//!   `fake cargo` stands a cargo in for `sitlogc build` that prints canned
//!   progress and makes an empty executable (a real build takes minutes;
//!   what `sitlogc` prints is real); and one `show WHAT` says what the
//!   block is: `stdout`, `stderr`, `output` (stderr then stdout), `json`
//!   (stdout laid out as `jq .` does), `file NAME` (a file the last
//!   command wrote), `source FILE` (a file of the repository, as it is),
//!   `files DIR` (a tree of DIR's files) or `syntax` (not an output: a
//!   piece of notation).
//!
//! A line `...` matches any number of lines; trailing spaces are ignored;
//! the scratch directory's path is shown as `~`.

use crate::support::{sitlogc, workspace};
use std::path::{Path, PathBuf};
use std::process::Stdio;

const PAGE: &str = "tutorial.md";

/// A fenced block of the page: its language, text, marker lines and the
/// line where it starts.
struct Block {
    lang: String,
    text: String,
    marker: Vec<String>,
    line: usize,
}

fn blocks(page: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut lines = page.lines().enumerate().peekable();
    let mut marker: Option<Vec<String>> = None;
    let mut pending: Option<Vec<String>> = None;
    while let Some((n, line)) = lines.next() {
        if let Some(m) = marker.as_mut() {
            if line.trim() == "-->" {
                pending = marker.take();
            } else {
                m.push(line.trim().to_owned());
            }
            continue;
        }
        if line.trim() == "<!-- test" {
            marker = Some(Vec::new());
            continue;
        }
        if let Some(lang) = line.strip_prefix("```") {
            let mut text = String::new();
            for (_, l) in lines.by_ref() {
                if l.starts_with("```") {
                    break;
                }
                text.push_str(l);
                text.push('\n');
            }
            out.push(Block {
                lang: lang.trim().to_owned(),
                text,
                marker: pending.take().unwrap_or_default(),
                line: n + 1,
            });
            continue;
        }
        // A marker belongs to the block right after it.
        pending = None;
    }
    out
}

/// Words of a command line, with '...' and "..." quoting.
fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, c) if c.is_whitespace() => out.extend(word.take()),
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    out.extend(word);
    out
}

/// A scratch directory: a copy of the tutorial's application at its path.
struct Scratch {
    dir: tempfile::TempDir,
    cargo: Option<PathBuf>,
    /// The text of the block above the one checked.
    above: String,
    /// The exit status of the last `sitlogc` run.
    status: std::cell::Cell<Option<i32>>,
}

impl Scratch {
    fn new() -> Scratch {
        let dir = tempfile::tempdir().unwrap();
        let app = workspace().join("dms/examples/tutorial");
        let copy = dir.path().join("dms/examples/tutorial");
        std::fs::create_dir_all(&copy).unwrap();
        for entry in std::fs::read_dir(&app).unwrap() {
            let p = entry.unwrap().path();
            std::fs::copy(&p, copy.join(p.file_name().unwrap())).unwrap();
        }
        Scratch {
            dir,
            cargo: None,
            above: String::new(),
            status: std::cell::Cell::new(None),
        }
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Links to the repository's `kb`, `benches`, `tests` and `dms` (each
    /// directory of it but the copied tutorial), for the guide's commands
    /// that name them.
    #[cfg(unix)]
    fn link_repository(&self) {
        use std::os::unix::fs::symlink;
        let root = workspace();
        for dir in ["kb", "benches", "tests"] {
            symlink(root.join(dir), self.path().join(dir)).unwrap();
        }
        for (parent, keep) in [("dms", "examples"), ("dms/examples", "tutorial")] {
            for entry in std::fs::read_dir(root.join(parent)).unwrap() {
                let entry = entry.unwrap();
                if entry.file_name() != keep {
                    let to = self.path().join(parent).join(entry.file_name());
                    symlink(entry.path(), to).unwrap();
                }
            }
        }
    }

    /// Runs `sitlogc ARGS` with `stdin`: (stdout, stderr), the scratch
    /// directory's path shown as `~`.
    fn run(&self, args: &[String], stdin: &str) -> (String, String) {
        let mut cmd = sitlogc();
        cmd.args(args)
            .current_dir(self.path())
            .env("HOME", self.path())
            .env_remove("XDG_CACHE_HOME")
            .env_remove("SITLOGC_CACHE_DIR")
            .env_remove("SITLOG_LIBRARY")
            .env_remove("SITLOG_HOME")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        if let Some(cargo) = &self.cargo {
            cmd.env("CARGO", cargo);
        }
        let mut child = cmd.spawn().unwrap();
        use std::io::Write;
        let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
        let out = child.wait_with_output().unwrap();
        self.status.set(out.status.code());
        let home = format!("{}", self.path().display());
        let text = |b: &[u8]| String::from_utf8_lossy(b).replace(&home, "~");
        (text(&out.stdout), text(&out.stderr))
    }

    /// Runs a command line of the page: `sitlogc ARGS [> FILE]` (stdout
    /// into FILE then, as a shell does) or `mkdir DIR`; `None` for any
    /// other command (not run).
    fn command(&self, line: &str, stdin: &str) -> Option<(String, String)> {
        let mut args = words(line);
        // A comment ends the command.
        if let Some(i) = args.iter().position(|a| a.starts_with('#')) {
            args.truncate(i);
        }
        // `| diff FILE -`: stdout compared with FILE (a golden test).
        let n = args.len();
        if n >= 5 && args[n - 4] == "|" && args[n - 3] == "diff" && args[n - 1] == "-" {
            let golden = args[n - 2].clone();
            args.truncate(n - 4);
            let (stdout, stderr) = self.command_words(args, stdin)?;
            let want = std::fs::read_to_string(self.path().join(&golden)).unwrap_or_default();
            if want != stdout {
                self.status.set(Some(1));
                return Some((format!("{stdout}\n(differs from {golden})"), stderr));
            }
            return Some((String::new(), stderr));
        }
        self.command_words(args, stdin)
    }

    /// [`Scratch::command`] on its words.
    fn command_words(&self, mut args: Vec<String>, stdin: &str) -> Option<(String, String)> {
        match args.first().map(String::as_str) {
            Some("mkdir") => {
                for dir in &args[1..] {
                    std::fs::create_dir_all(self.path().join(dir)).unwrap();
                }
                self.status.set(Some(0));
                Some((String::new(), String::new()))
            }
            Some("sitlogc") => {
                let into = match args.len() {
                    n if n >= 3 && args[n - 2] == ">" => {
                        let file = args.pop();
                        args.pop();
                        file
                    }
                    _ => None,
                };
                let (stdout, stderr) = self.run(&args[1..], stdin);
                match into {
                    Some(file) => {
                        std::fs::write(self.path().join(file), stdout).unwrap();
                        Some((String::new(), stderr))
                    }
                    None => Some((stdout, stderr)),
                }
            }
            _ => None,
        }
    }

    /// A cargo that prints what a build prints and makes an empty
    /// executable where `sitlogc build` looks for it.
    #[cfg(unix)]
    fn fake_cargo(&mut self) {
        use std::os::unix::fs::PermissionsExt;
        let path = self.path().join("fake-cargo");
        std::fs::write(
            &path,
            "#!/bin/sh\n\
             [ \"$1\" = build ] || exit 0\n\
             while [ $# -gt 0 ]; do\n\
               [ \"$1\" = --target-dir ] && target=$2\n\
               [ \"$1\" = --manifest-path ] && manifest=$2\n\
               shift\n\
             done\n\
             name=$(sed -n 's/^name = \"\\(.*\\)\"/\\1/p' \"$manifest\" | head -1)\n\
             mkdir -p \"$target/release\"\n\
             printf '#!/bin/sh\\n' > \"$target/release/$name\"\n\
             chmod +x \"$target/release/$name\"\n\
             echo '   Compiling ...' >&2\n\
             echo '    Finished `release` profile [optimized] target(s) in 2m 17s' >&2\n",
        )
        .unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
        self.cargo = Some(path);
    }
}

/// Whether `actual` is `expected`, a line `...` of `expected` standing for
/// any number of lines; trailing spaces do not count.
fn matches(expected: &[&str], actual: &[&str]) -> bool {
    match expected.split_first() {
        None => actual.is_empty(),
        Some((e, rest)) if e.trim() == "..." => {
            (0..=actual.len()).any(|skip| matches(rest, &actual[skip..]))
        }
        Some((e, rest)) => match actual.split_first() {
            Some((a, more)) => e.trim_end() == a.trim_end() && matches(rest, more),
            None => false,
        },
    }
}

fn lines(text: &str) -> Vec<&str> {
    text.lines().collect()
}

/// JSON text laid out as `jq .` does (two spaces, `"key": value`).
fn jq(text: &str) -> String {
    let mut out = String::new();
    let mut depth = 0usize;
    let mut chars = text.trim().chars().peekable();
    let newline = |out: &mut String, depth: usize| {
        out.push('\n');
        out.push_str(&"  ".repeat(depth));
    };
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                out.push(c);
                while let Some(s) = chars.next() {
                    out.push(s);
                    match s {
                        '\\' => out.extend(chars.next()),
                        '"' => break,
                        _ => {}
                    }
                }
            }
            '{' | '[' => {
                let close = if c == '{' { '}' } else { ']' };
                if chars.peek() == Some(&close) {
                    chars.next();
                    out.push(c);
                    out.push(close);
                } else {
                    out.push(c);
                    depth += 1;
                    newline(&mut out, depth);
                }
            }
            '}' | ']' => {
                depth = depth.saturating_sub(1);
                newline(&mut out, depth);
                out.push(c);
            }
            ',' => {
                out.push(c);
                newline(&mut out, depth);
            }
            ':' => out.push_str(": "),
            c if c.is_whitespace() => {}
            c => out.push(c),
        }
    }
    out.push('\n');
    out
}

/// Checks a console block: runs its `$ sitlogc` lines.
fn check_console(block: &Block, scratch: &Scratch) -> Result<(), String> {
    let mut sessions: Vec<(String, Vec<&str>)> = Vec::new();
    for line in block.text.lines() {
        match line.strip_prefix("$ ") {
            Some(cmd) => sessions.push((cmd.to_owned(), Vec::new())),
            None => match sessions.last_mut() {
                Some((_, shown)) => shown.push(line),
                None => return Err(format!("output before any command: {line:?}")),
            },
        }
    }
    for (cmd, shown) in sessions {
        // What the user types at the prompt, and the prompt as it shows
        // without a terminal to echo it.
        let mut stdin = String::new();
        let mut expected = Vec::new();
        for line in &shown {
            match line.strip_prefix("|: ") {
                Some(typed) => {
                    stdin.push_str(typed);
                    stdin.push('\n');
                    expected.push("|: ".to_owned());
                }
                None => expected.push((*line).to_owned()),
            }
        }
        let Some((stdout, stderr)) = scratch.command(&cmd, &stdin) else {
            if !shown.is_empty() {
                return Err(format!("`{cmd}` is not run, but output is shown for it"));
            }
            continue;
        };
        // The prompt's line goes on with what is printed next.
        let actual = format!("{stderr}{stdout}").replace("|: ", "|: \n");
        let expected: Vec<&str> = expected.iter().map(String::as_str).collect();
        if !matches(&expected, &lines(&actual)) {
            return Err(format!(
                "`{cmd}` prints\n{actual}\nbut the page shows\n{}",
                shown.join("\n")
            ));
        }
    }
    Ok(())
}

/// Checks a block with a marker.
fn check_marked(block: &Block, scratch: &mut Scratch) -> Result<(), String> {
    let mut last: Option<(String, String)> = None;
    let mut show = None;
    let mut marker = block.marker.iter();
    while let Some(line) = marker.next() {
        if let Some(cmd) = line.strip_prefix("$ ") {
            last = Some(
                scratch
                    .command(cmd, "")
                    .ok_or_else(|| format!("only sitlogc and mkdir are run: {cmd}"))?,
            );
        } else if let Some(rest) = line.strip_prefix("write ") {
            let (file, text) = rest.split_once(": ").ok_or("write FILE: TEXT")?;
            let text = match text {
                "(the block above)" => scratch.above.clone(),
                text => text.replace("\\n", "\n"),
            };
            let path = scratch.path().join(file);
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
            }
            std::fs::write(path, text).map_err(|e| e.to_string())?;
        } else if let Some(rest) = line.strip_prefix("replace ") {
            let (file, old) = rest.split_once(": ").ok_or("replace FILE: OLD")?;
            let new = marker
                .next()
                .and_then(|l| l.strip_prefix("by:"))
                .map(str::trim_start)
                .ok_or("`replace FILE: OLD` is followed by `by: NEW`")?;
            let (old, new) = (old.replace("\\n", "\n"), new.replace("\\n", "\n"));
            let (old, new) = (old.as_str(), new.as_str());
            let path = scratch.path().join(file);
            let text = std::fs::read_to_string(&path).map_err(|e| format!("{file}: {e}"))?;
            if !text.contains(old) {
                return Err(format!("no `{old}` in {file}"));
            }
            std::fs::write(&path, text.replacen(old, new, 1)).map_err(|e| e.to_string())?;
        } else if line == "run" || line.starts_with("skip:") {
            // Said of a command block (see `check_command_block`).
        } else if line == "fake cargo" {
            #[cfg(unix)]
            scratch.fake_cargo();
        } else if let Some(what) = line.strip_prefix("show ") {
            show = Some(what.to_owned());
        } else {
            return Err(format!("unknown test instruction `{line}`"));
        }
    }
    let show = show.ok_or("the marker says nothing to `show`")?;
    let output = |which: &str| -> Result<String, String> {
        let (stdout, stderr) = last.clone().ok_or("no command was run")?;
        Ok(match which {
            "stdout" => stdout,
            "stderr" => stderr,
            _ => format!("{stderr}{stdout}"),
        })
    };
    let actual = match show.split_once(' ').unwrap_or((show.as_str(), "")) {
        ("stdout" | "stderr" | "output", _) => output(&show)?,
        ("json", _) => jq(&output("stdout")?),
        ("file", name) => std::fs::read_to_string(scratch.path().join(name))
            .map_err(|e| format!("{name}: {e}"))?,
        ("source", file) => {
            std::fs::read_to_string(workspace().join(file)).map_err(|e| format!("{file}: {e}"))?
        }
        ("files", dir) => {
            // The tree's entries: the last word before the description.
            let mut named: Vec<String> = block
                .text
                .lines()
                .skip(1)
                .filter_map(|l| {
                    l.trim_start_matches(['│', '├', '└', '─', ' '])
                        .split_whitespace()
                        .next()
                        .map(str::to_owned)
                })
                .collect();
            let mut files: Vec<String> = std::fs::read_dir(workspace().join(dir))
                .map_err(|e| e.to_string())?
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            named.sort();
            files.sort();
            return if named == files {
                Ok(())
            } else {
                Err(format!("{dir} holds {files:?}, the tree shows {named:?}"))
            };
        }
        ("syntax", _) => return Ok(()),
        _ => return Err(format!("unknown `show {show}`")),
    };
    if matches(&lines(&block.text), &lines(&actual)) {
        Ok(())
    } else {
        Err(format!(
            "it is\n{actual}\nbut the page shows\n{}",
            block.text
        ))
    }
}

/// Checks the blocks of `page` (below `docs/guide/`): every block, or
/// (`all` false) those with a marker; the number of blocks checked.
fn check_page(page: &str, all: bool) -> usize {
    let text = std::fs::read_to_string(workspace().join("docs/guide").join(page)).unwrap();
    let blocks = blocks(&text);
    let mut problems = Vec::new();
    let mut checked = 0;
    let mut above: Option<&Block> = None;
    for block in &blocks {
        let mut scratch = Scratch::new();
        if let Some(above) = above {
            scratch.above = above.text.clone();
        }
        above = Some(block);
        if block.marker.iter().any(|l| l.starts_with("skip:")) {
            continue;
        }
        let result = match (block.lang.as_str(), block.marker.is_empty()) {
            (_, true) if !all => continue,
            ("console", _) => {
                check_marked_setup(block, &mut scratch).and_then(|_| check_console(block, &scratch))
            }
            // Run by the README and guide test when marked `run`.
            ("sh", _) => Ok(()),
            (_, true) => Err("no `<!-- test` marker says what this block is".to_owned()),
            (_, false) => check_marked(block, &mut scratch),
        };
        checked += 1;
        if let Err(e) = result {
            problems.push(format!(
                "docs/guide/{page}:{}: ```{}: {e}",
                block.line, block.lang
            ));
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n\n"));
    checked
}

#[test]
fn every_block_of_the_tutorial_is_what_sitlogc_does() {
    assert!(check_page(PAGE, true) > 20);
}

/// The language page's examples with a marker (the patterns of issue 30:
/// list expectations, where DM parameters are visible, giving up after N
/// misunderstandings) run as shown.
#[test]
fn the_marked_examples_of_the_language_page_run_as_shown() {
    assert!(check_page("language.md", false) >= 3);
}

/// A console block's marker may prepare files and a fake cargo.
fn check_marked_setup(block: &Block, scratch: &mut Scratch) -> Result<(), String> {
    if block.marker.is_empty() {
        return Ok(());
    }
    let mut setup = Block {
        lang: String::new(),
        text: String::new(),
        marker: block.marker.clone(),
        line: block.line,
    };
    setup.marker.push("show syntax".to_owned());
    check_marked(&setup, scratch)
}

/// The marked examples of the page on `sitlogc test` (issue 40) run as shown.
#[test]
fn the_marked_examples_of_the_app_testing_page_run_as_shown() {
    assert!(check_page("testing-apps.md", false) >= 1);
}

#[test]
fn the_checker_of_the_page_catches_drift() {
    assert!(matches(&["a", "...", "d"], &["a", "b", "c", "d"]));
    assert!(matches(&["a", "..."], &["a"]));
    assert!(!matches(&["a", "b"], &["a", "c"]));
    assert_eq!(
        jq(r#"{"a":[1,{"b":"x,y"}],"c":[]}"#),
        "{\n  \"a\": [\n    1,\n    {\n      \"b\": \"x,y\"\n    }\n  ],\n  \"c\": []\n}\n"
    );
    assert_eq!(words("run 'a b' c"), ["run", "a b", "c"]);
}

/// Runs an `sh` block marked `run`: each line (comments and blank lines
/// aside) is a `sitlogc` or `mkdir` command, run in turn, and succeeds.
fn check_sh(block: &Block, scratch: &Scratch) -> Result<(), String> {
    for line in block.text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (stdout, stderr) = scratch
            .command(line, "")
            .ok_or_else(|| format!("only sitlogc and mkdir are run: {line}"))?;
        if scratch.status.get() != Some(0) {
            return Err(format!(
                "`{line}` exits {:?}\n{stderr}{stdout}",
                scratch.status.get()
            ));
        }
    }
    Ok(())
}

/// Checks a command block (`sh` or `console`) of any page; `Ok(false)`
/// when its marker says `skip: REASON`, or another test checks it.
fn check_command_block(page: &str, block: &Block, above: &str) -> Result<bool, String> {
    if let Some(reason) = block.marker.iter().find_map(|l| l.strip_prefix("skip:")) {
        return if reason.trim().len() < 8 {
            Err("`skip:` needs a reason".to_owned())
        } else {
            Ok(false)
        };
    }
    // The tutorial's test checks its console blocks, and the language and
    // app-testing pages' tests their marked ones.
    let elsewhere = match page {
        "tutorial.md" => block.lang == "console",
        "language.md" | "testing-apps.md" => !block.marker.is_empty() && block.lang == "console",
        _ => false,
    };
    if elsewhere {
        return Ok(false);
    }
    let mut scratch = Scratch::new();
    scratch.above = above.to_owned();
    #[cfg(unix)]
    scratch.link_repository();
    check_marked_setup(block, &mut scratch)?;
    match block.lang.as_str() {
        "console" => check_console(block, &scratch)?,
        _ if block.marker.iter().any(|l| l == "run") => check_sh(block, &scratch)?,
        _ => {
            return Err("a command block is marked `<!-- test` with `run` \
                        (its commands are run) or `skip: REASON`"
                .to_owned())
        }
    }
    Ok(true)
}

/// Every command block (`sh`, `console`) of README.md and of the guide is
/// run as shown, or its marker says why not: `skip: REASON` (ROS 2, a
/// release build, a browser, the original's tree, a synopsis with
/// placeholders such as `APP`) (issue 40). Only fast blocks are run.
#[test]
fn every_command_block_of_the_readme_and_the_guide_is_run_or_says_why_not() {
    let root = workspace();
    let mut pages = vec![("README.md".to_owned(), root.join("README.md"))];
    let mut guide: Vec<_> = std::fs::read_dir(root.join("docs/guide"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), p))
        .collect();
    guide.sort();
    pages.extend(guide);
    let mut problems = Vec::new();
    let mut run = 0;
    for (name, path) in &pages {
        let text = std::fs::read_to_string(path).unwrap();
        let blocks = blocks(&text);
        let mut above = "";
        for block in &blocks {
            if matches!(block.lang.as_str(), "sh" | "console" | "bash" | "shell") {
                match check_command_block(name, block, above) {
                    Ok(true) => run += 1,
                    Ok(false) => {}
                    Err(e) => {
                        problems.push(format!("{name}:{}: ```{}: {e}", block.line, block.lang))
                    }
                }
            }
            above = &block.text;
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n\n"));
    assert!(run >= 4, "only {run} command blocks are run");
}
