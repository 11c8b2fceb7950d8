//! Embeds the sources of the workspace crates a compiled task links (the
//! runtime and what it needs), the workspace manifest and `Cargo.lock` into
//! `sitlogc`, so that `sitlogc build` works without the checkout it was
//! built from (see `src/package.rs`, which extracts them into the user's
//! cache directory), and `src/legacy.rs` (a task of `sitlogc build --legacy`
//! compiles it in). Writes `$OUT_DIR/embedded_runtime.rs`: the files as
//! `(relative path, bytes)` and a hash of them all that names the extracted
//! copy.
//!
//! It also embeds the behaviour library (`dms/behaviors/`, its DMs and its
//! Prolog grammar) as `$OUT_DIR/embedded_library.rs`: the files named as an
//! application names them (`behaviors/say.dm`), which `sitlogc` reads when
//! an application has no copy of its own (see `src/library.rs`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The workspace crates a generated task package depends on, directly
/// (runtime, robot; debug with `sitlogc build --debugger`) or through them
/// (features `prolog`, `sim`, `view`), and the robot over ROS 2 (`ros`,
/// with `sitlogc build --ros2`).
const CRATES: &[&str] = &[
    "syntax", "runtime", "kb", "robot", "sim", "infer", "view", "graph", "debug", "ros",
];

fn main() {
    let manifest_dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap());
    let root = manifest_dir.parent().unwrap().to_path_buf();
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").unwrap());
    let mut files: Vec<(String, PathBuf)> = Vec::new();
    for krate in CRATES {
        let dir = root.join(krate);
        println!(
            "cargo:rerun-if-changed={}",
            dir.join("Cargo.toml").display()
        );
        println!("cargo:rerun-if-changed={}", dir.join("src").display());
        files.push((format!("{krate}/Cargo.toml"), dir.join("Cargo.toml")));
        if dir.join("build.rs").is_file() {
            println!("cargo:rerun-if-changed={}", dir.join("build.rs").display());
            files.push((format!("{krate}/build.rs"), dir.join("build.rs")));
        }
        walk(&dir.join("src"), &format!("{krate}/src"), &mut files);
    }
    // The legacy profile, compiled into a task of `sitlogc build --legacy`
    // as a module of its own (see `src/legacy.rs`).
    let legacy = manifest_dir.join("src").join("legacy.rs");
    println!("cargo:rerun-if-changed={}", legacy.display());
    files.push(("cli/src/legacy.rs".to_owned(), legacy));
    let lock = root.join("Cargo.lock");
    println!("cargo:rerun-if-changed={}", lock.display());
    files.push(("Cargo.lock".to_owned(), lock));
    // The workspace manifest, its members cut down to the embedded crates.
    let manifest = root.join("Cargo.toml");
    println!("cargo:rerun-if-changed={}", manifest.display());
    let text = std::fs::read_to_string(&manifest).expect("the workspace Cargo.toml");
    let embedded_manifest = out_dir.join("workspace-Cargo.toml");
    std::fs::write(&embedded_manifest, workspace_manifest(&text)).unwrap();
    files.push(("Cargo.toml".to_owned(), embedded_manifest));
    files.sort();

    // FNV-1a over paths and contents: stable across compilers and runs.
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for b in bytes {
            hash ^= u64::from(*b);
            hash = hash.wrapping_mul(0x0100_0000_01b3);
        }
    };
    let mut code = String::from(
        "/// The embedded workspace files: (path relative to the workspace root, contents).\n",
    );
    code.push_str("pub(crate) static RUNTIME_FILES: &[(&str, &[u8])] = &[\n");
    for (rel, path) in &files {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        feed(rel.as_bytes());
        feed(&[0]);
        feed(&(bytes.len() as u64).to_le_bytes());
        feed(&bytes);
        writeln!(
            code,
            "    ({rel:?}, include_bytes!({:?})),",
            path.display().to_string()
        )
        .unwrap();
    }
    code.push_str("];\n");
    writeln!(
        code,
        "/// A hash of [`RUNTIME_FILES`] (paths and contents)."
    )
    .unwrap();
    writeln!(
        code,
        "pub(crate) const RUNTIME_HASH: &str = \"{hash:016x}\";"
    )
    .unwrap();
    std::fs::write(out_dir.join("embedded_runtime.rs"), code).unwrap();
    embed_library(&root, &out_dir);
}

/// Writes `embedded_library.rs`: `LIBRARY_FILES`, every file below
/// `dms/behaviors/` as `(behaviors/…, bytes)`, sorted.
fn embed_library(root: &Path, out_dir: &Path) {
    let dir = root.join("dms").join("behaviors");
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files = Vec::new();
    walk(&dir, "behaviors", &mut files);
    for (_, path) in &files {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    files.sort();
    let mut code = String::from(
        "/// The behaviour library: (name as applications write it, contents).\n\
         pub(crate) static LIBRARY_FILES: &[(&str, &[u8])] = &[\n",
    );
    for (rel, path) in &files {
        writeln!(
            code,
            "    ({rel:?}, include_bytes!({:?})),",
            path.display().to_string()
        )
        .unwrap();
    }
    code.push_str("];\n");
    std::fs::write(out_dir.join("embedded_library.rs"), code).unwrap();
}

/// Every file below `dir`, as `prefix/…` (sorted later).
fn walk(dir: &Path, prefix: &str, out: &mut Vec<(String, PathBuf)>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let entry = entry.unwrap();
        let name = entry.file_name().to_string_lossy().into_owned();
        let path = entry.path();
        let rel = format!("{prefix}/{name}");
        if path.is_dir() {
            walk(&path, &rel, out);
        } else {
            out.push((rel, path));
        }
    }
}

/// The workspace manifest with `members` the embedded crates, no
/// `default-members` and no profiles (a dependency's workspace only lends
/// its `[workspace.package]` and `[workspace.dependencies]`).
fn workspace_manifest(text: &str) -> String {
    let mut out = String::from(
        "# The workspace of the runtime crates embedded in sitlogc (see cli/build.rs).\n",
    );
    let mut table = String::new();
    let mut skipping_array = false;
    for line in text.lines() {
        let trimmed = line.trim();
        if skipping_array {
            skipping_array = !trimmed.contains(']');
            continue;
        }
        if trimmed.starts_with('[') && !trimmed.starts_with("[[") {
            table = trimmed.to_owned();
            if table == "[workspace]" {
                out.push_str(line);
                out.push('\n');
                let members: Vec<String> = CRATES.iter().map(|c| format!("{c:?}")).collect();
                writeln!(out, "members = [{}]", members.join(", ")).unwrap();
                continue;
            }
        }
        if table.starts_with("[profile") {
            continue;
        }
        if table == "[workspace]"
            && (trimmed.starts_with("members") || trimmed.starts_with("default-members"))
        {
            skipping_array = trimmed.contains('[') && !trimmed.contains(']');
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}
