//! `sitlogc build`: an application compiled to one executable. Generates a
//! Cargo package that depends on the runtime crates by path, builds it with
//! cargo (progress shown on stderr; `--offline` when the dependencies are
//! already on this machine) into one shared target dir (so the build cache
//! is reused between applications and runs), and copies the executable to
//! the requested file. The executable takes the options of `sitlogc run`
//! (see `sitlog_robot::cli`).
//!
//! Nothing here needs the checkout `sitlogc` was built from: the sources of
//! the runtime crates, the workspace manifest and `Cargo.lock` are embedded
//! in the binary (`cli/build.rs`) and extracted once per version and
//! content hash into the user's cache directory ([`cache_dir`]), which also
//! holds the generated packages and the target dir:
//!
//! ```text
//! <cache>/runtime/<version>-<hash>/   the embedded workspace (runtime, robot, …)
//! <cache>/apps/<app>/                 one generated package per application
//! <cache>/target/                     the shared cargo target dir
//! ```

use sitlog_compiler::build::{app_ident, write_if_changed, Compiled, Error};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

include!(concat!(env!("OUT_DIR"), "/embedded_runtime.rs"));

/// The environment variable that chooses the cache directory.
pub const CACHE_ENV: &str = "SITLOGC_CACHE_DIR";

/// Where `sitlogc build` keeps its files: `$SITLOGC_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/sitlogc`, else `~/.cache/sitlogc` (on Windows
/// `%LOCALAPPDATA%\sitlogc`).
pub fn cache_dir() -> Result<PathBuf, Error> {
    let var = |name: &str| {
        std::env::var_os(name)
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
    };
    if let Some(dir) = std::env::var_os(CACHE_ENV).filter(|v| !v.is_empty()) {
        let dir = PathBuf::from(dir);
        return Ok(if dir.is_absolute() {
            dir
        } else {
            std::env::current_dir()
                .map_err(|e| Error {
                    messages: vec![format!("cannot read the current directory: {e}")],
                })?
                .join(dir)
        });
    }
    if let Some(dir) = var("XDG_CACHE_HOME") {
        return Ok(dir.join("sitlogc"));
    }
    if cfg!(windows) {
        if let Some(dir) = var("LOCALAPPDATA") {
            return Ok(dir.join("sitlogc"));
        }
    }
    if let Some(home) = var("HOME") {
        return Ok(home.join(".cache").join("sitlogc"));
    }
    Err(Error {
        messages: vec![format!(
            "no cache directory: set {CACHE_ENV} (or XDG_CACHE_HOME, or HOME) to an absolute path"
        )],
    })
}

/// The embedded runtime workspace's directory under `cache`, named after
/// this sitlogc's version and the hash of the embedded files.
pub fn runtime_dir(cache: &Path) -> PathBuf {
    cache
        .join("runtime")
        .join(format!("{}-{RUNTIME_HASH}", env!("CARGO_PKG_VERSION")))
}

/// Extracts the embedded runtime workspace into `cache` unless it is there
/// already; returns its directory. Atomic: the files are written into a
/// temporary directory that is then renamed, so a killed or concurrent
/// `sitlogc` never leaves (or uses) half a copy.
pub fn extract_runtime(cache: &Path) -> Result<PathBuf, Error> {
    let dir = runtime_dir(cache);
    if dir.is_dir() {
        return Ok(dir);
    }
    let err = |what: &Path, e: std::io::Error| Error {
        messages: vec![format!("cannot write {}: {e}", what.display())],
    };
    let parent = dir.parent().expect("runtime_dir has a parent");
    std::fs::create_dir_all(parent).map_err(|e| err(parent, e))?;
    let tmp = tempfile::Builder::new()
        .prefix(".extract-")
        .tempdir_in(parent)
        .map_err(|e| err(parent, e))?;
    for (rel, bytes) in RUNTIME_FILES {
        let path = tmp.path().join(rel);
        if let Some(d) = path.parent() {
            std::fs::create_dir_all(d).map_err(|e| err(d, e))?;
        }
        std::fs::write(&path, bytes).map_err(|e| err(&path, e))?;
    }
    match std::fs::rename(tmp.path(), &dir) {
        Ok(()) => {
            let _ = tmp.keep();
            Ok(dir)
        }
        // Another sitlogc extracted it meanwhile: use theirs (ours is removed).
        Err(_) if dir.is_dir() => Ok(dir),
        Err(e) => Err(err(&dir, e)),
    }
}

/// Where things are: the runtime crates to depend on, where packages are
/// generated, and the target dir.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The `runtime/` crate directory (absolute).
    pub runtime: PathBuf,
    /// The `robot/` crate directory (absolute): the command line, KB
    /// functions and simulated robot a compiled task links.
    pub robot: PathBuf,
    /// The `debug/` crate directory (absolute): the step debugger a task
    /// built with `sitlogc build --debugger` links.
    pub debug: PathBuf,
    /// The `ros/` crate directory (absolute): the robot over ROS 2 a task
    /// built with `sitlogc build --ros2` (or with a `ros2.toml`) links.
    pub ros: PathBuf,
    /// The `Cargo.lock` copied into new packages so that they use the
    /// dependency versions sitlogc was tested with (and can build offline).
    pub lockfile: Option<PathBuf>,
    /// The directory of the generated packages (one per application).
    pub packages: PathBuf,
    /// The shared cargo target dir.
    pub target: PathBuf,
}

impl Layout {
    /// The layout in the user's cache directory ([`cache_dir`]), the
    /// embedded runtime extracted there if needed.
    pub fn user() -> Result<Layout, Error> {
        Layout::in_cache(&cache_dir()?)
    }

    /// The layout in `cache`, the embedded runtime extracted there if needed.
    pub fn in_cache(cache: &Path) -> Result<Layout, Error> {
        let root = extract_runtime(cache)?;
        Ok(Layout {
            runtime: root.join("runtime"),
            robot: root.join("robot"),
            debug: root.join("debug"),
            ros: root.join("ros"),
            lockfile: Some(root.join("Cargo.lock")),
            packages: cache.join("apps"),
            target: cache.join("target"),
        })
    }
}

/// The dependencies of the Prolog engine (scryer-prolog) that a task never
/// runs: its cryptography, HTML and XML parsers and async runtime
/// (predicates of libraries the engine loads only on request; not `chrono`
/// and `futures-util`, which the ROS 2 stack runs), compiled
/// unoptimised in `sitlogc build`'s release profile. A fifth of a robot
/// application's first build is the engine; these crates ahead of it on the
/// critical path (docs/guide/compiling.md, "Robot builds", issue 40).
const PROLOG_PROFILE: &str = "\
# Dependencies of the Prolog engine that a task does not run (cryptography,\n\
# HTML, XML, async): not optimised, a shorter first build.\n\
[profile.release.package.crrl]\nopt-level = 0\n\
[profile.release.package.ring]\nopt-level = 0\n\
[profile.release.package.scraper]\nopt-level = 0\n\
[profile.release.package.html5ever]\nopt-level = 0\n\
[profile.release.package.markup5ever]\nopt-level = 0\n\
[profile.release.package.selectors]\nopt-level = 0\n\
[profile.release.package.cssparser]\nopt-level = 0\n\
[profile.release.package.roxmltree]\nopt-level = 0\n\
[profile.release.package.ego-tree]\nopt-level = 0\n\
[profile.release.package.blake2]\nopt-level = 0\n\
[profile.release.package.sha2]\nopt-level = 0\n\
[profile.release.package.sha3]\nopt-level = 0\n\
[profile.release.package.ripemd]\nopt-level = 0\n\
[profile.release.package.tokio]\nopt-level = 0\n\n";

/// A task of the original's tree (`sitlogc build --legacy`): what its
/// `main` needs besides the program, found when it is built.
#[derive(Clone, Debug, Default)]
pub struct Legacy {
    /// The application's directory relative to the tree it was built from
    /// (`apps/test_behaviors`): at run time, relative to the tree the task
    /// is given (its Prolog files' relative consults are resolved there, as
    /// `sitlogc run --legacy` resolves them).
    pub app_in_home: Option<String>,
    /// The application's first `caption/2` fact
    /// (`crate::legacy::first_caption`).
    pub caption: Option<(String, String)>,
}

/// Writes the Cargo package of a compiled application; returns its
/// directory and package name. With `debugger` the task also links the
/// step debugger (`sitlog_debug::task_main`: it runs under the debugger,
/// as `sitlogc debug` runs the sources). With `ros2`, or when the
/// application has a `ros2.toml` (and without `debugger`), the task also
/// links the robot over ROS 2 (`--robot ros2`, sitlog-ros). With `legacy`
/// (not with `debugger` or `ros2`) the task runs as `sitlogc run --legacy`
/// runs the application: its `main` is `sitlog_robot::main_legacy`, with
/// `crate::legacy` compiled in as a module (the same file), and it links
/// the Prolog engine, sitlog-syntax and sitlog-kb.
pub fn write_package(
    compiled: &Compiled,
    app: &Path,
    layout: &Layout,
    debugger: bool,
    ros2: bool,
    legacy: Option<&Legacy>,
) -> Result<(PathBuf, String), Error> {
    let name = app_ident(app);
    let package = format!("sitlog-app-{}", name.replace('_', "-").trim_matches('-'));
    let dir = layout.packages.join(&name);
    let io = |what: &Path, e: std::io::Error| Error {
        messages: vec![format!("cannot write {}: {e}", what.display())],
    };
    let path_of = |p: &Path| p.display().to_string().replace('\\', "/");
    let runtime = path_of(&layout.runtime);
    let robot = path_of(&layout.robot);
    let has_prolog = legacy.is_some()
        || compiled.files.iter().any(|f| {
            f.file_name()
                .is_some_and(|n| n == "user_functions.pl" || n == "templates.pl")
        });
    // The workspace root of the embedded crates (`runtime/`'s parent).
    let root = layout.runtime.parent().unwrap_or(&layout.runtime);
    let assets = sitlog_robot::Assets::from_app(app).map_err(|e| Error {
        messages: vec![e.to_string()],
    })?;
    let ros2 = !debugger && legacy.is_none() && (ros2 || assets.ros2.is_some());
    let manifest = format!(
        "# @generated by `sitlogc build` from `{src}`\n\
         [package]\nname = \"{package}\"\nversion = \"0.1.0\"\nedition = \"2021\"\npublish = false\n\n\
         [[bin]]\nname = \"{package}\"\npath = \"src/main.rs\"\n\n\
         [dependencies]\n\
         sitlog-runtime = {{ path = \"{runtime}\"{features} }}\n\
         sitlog-robot = {{ path = \"{robot}\", default-features = false{robot_features} }}\n\
         {debug_dep}{ros_dep}{legacy_deps}\n\
         # Not a member of the enclosing workspace.\n[workspace]\n\n\
         # The edit loop (issue 40, docs/guide/compiling.md): the dependencies\n\
         # (runtime, simulator, Prolog engine) are optimised once and cached; the\n\
         # task's own crate is rebuilt incrementally; no LTO, no debug info.\n\
         [profile.release]\nlto = \"off\"\ncodegen-units = 16\ndebug = false\n\n\
         [profile.release.package.{package}]\nincremental = true\n\n\
         # `sitlogc build --debug`: the same, unoptimised. The runtime crates are\n\
         # path dependencies, which cargo compiles incrementally by default; they\n\
         # never change in the cache, so that only costs time and disk.\n\
         [profile.dev]\nincremental = false\n\n\
         [profile.dev.package.{package}]\nincremental = true\n\n\
         {prolog_profile}\
         # `sitlogc build --lto`: whole-program optimisation, the fastest code.\n\
         [profile.lto]\ninherits = \"release\"\nlto = \"fat\"\ncodegen-units = 1\n\n\
         [profile.lto.package.{package}]\nincremental = false\n",
        src = app.display(),
        // The embedded Prolog engine only where the application has Prolog sources.
        features = if has_prolog { ", features = [\"prolog\"]" } else { "" },
        prolog_profile = if has_prolog { PROLOG_PROFILE } else { "" },
        // `--debugger`: the step debugger (its own main, see `task_main` below).
        debug_dep = if debugger {
            format!("sitlog-debug = {{ path = \"{}\" }}\n", path_of(&layout.debug))
        } else {
            String::new()
        },
        // The simulator only where the application has a world; the live view always.
        // `--ros2`: the robot over ROS 2 (its own main, see `task_main` below).
        ros_dep = if ros2 {
            format!("sitlog-ros = {{ path = \"{}\" }}\n", path_of(&layout.ros))
        } else {
            String::new()
        },
        // `--legacy`: what `legacy.rs` uses besides the runtime and robot.
        legacy_deps = if legacy.is_some() {
            format!(
                "sitlog-syntax = {{ path = \"{}\" }}\nsitlog-kb = {{ path = \"{}\" }}\n",
                path_of(&root.join("syntax")),
                path_of(&root.join("kb"))
            )
        } else {
            String::new()
        },
        robot_features = if assets.world.is_some() {
            ", features = [\"sim\", \"view\"]"
        } else {
            ", features = [\"view\"]"
        },
    );
    let embed = |s: &Option<sitlog_robot::TextFile>| match s {
        Some(s) => format!(
            "Some(sitlog_robot::TextFile {{ name: {:?}.to_owned(), text: {:?}.to_owned() }})",
            s.name, s.text
        ),
        None => "None".to_owned(),
    };
    let main = format!(
        "// @generated by `sitlogc build` from `{src}`. Do not edit.\n\n\
         mod program;\n\n\
         fn main() -> std::process::ExitCode {{\n    \
         let assets = sitlog_robot::Assets {{\n        \
         app_name: {app_name:?}.to_owned(),\n        \
         world: {world},\n        \
         kb: {kb},\n        \
         ros2: {ros2_file},\n        \
         diagram: {diagram},\n    \
         }};\n    \
         match program::functions() {{\n        \
         Ok(functions) => {task_main}(program::program(), functions, &assets{robot}),\n        \
         Err(e) => sitlog_robot::main_failed(&assets, &e),\n    \
         }}\n}}\n",
        src = app.display(),
        app_name = assets.app_name,
        task_main = if debugger {
            "sitlog_debug::task_main"
        } else if ros2 {
            "sitlog_robot::main_with_robot"
        } else {
            "sitlog_robot::main"
        },
        robot = if ros2 { ", sitlog_ros::hook" } else { "" },
        ros2_file = embed(&assets.ros2),
        world = embed(&assets.world),
        kb = embed(&assets.kb),
        diagram = match diagram_json(app) {
            Some(json) => format!("Some({json:?}.to_owned())"),
            None => "None".to_owned(),
        },
    );
    let main = match legacy {
        Some(legacy) => legacy_main(
            app,
            &assets,
            legacy,
            &path_of(&root.join("cli/src/legacy.rs")),
        ),
        None => main,
    };
    let files = [
        (dir.join("Cargo.toml"), manifest),
        (dir.join("src/main.rs"), main),
        (dir.join("src/program.rs"), compiled.to_file_string()),
    ];
    for (path, text) in &files {
        write_if_changed(path, text).map_err(|e| io(path, e))?;
    }
    let lock = dir.join("Cargo.lock");
    if let (Some(src), false) = (&layout.lockfile, lock.exists()) {
        std::fs::copy(src, &lock).map_err(|e| io(&lock, e))?;
    }
    Ok((dir, package))
}

/// The `main.rs` of a task of the original's tree (see [`Legacy`]):
/// `legacy_rs` is the embedded copy of `cli/src/legacy.rs`.
fn legacy_main(
    app: &Path,
    assets: &sitlog_robot::Assets,
    legacy: &Legacy,
    legacy_rs: &str,
) -> String {
    let embed = |s: &Option<sitlog_robot::TextFile>| match s {
        Some(s) => format!(
            "Some(sitlog_robot::TextFile {{ name: {:?}.to_owned(), text: {:?}.to_owned() }})",
            s.name, s.text
        ),
        None => "None".to_owned(),
    };
    format!(
        "// @generated by `sitlogc build --legacy` from `{src}`. Do not edit.\n\n\
         mod program;\n\n\
         /// The legacy profile of `sitlogc run --legacy`: the same file.\n\
         #[allow(dead_code)]\n\
         #[path = {legacy_rs:?}]\n\
         mod legacy;\n\n\
         fn main() -> std::process::ExitCode {{\n    \
         let assets = sitlog_robot::Assets {{\n        \
         app_name: {app_name:?}.to_owned(),\n        \
         world: {world},\n        \
         kb: {kb},\n        \
         ros2: None,\n        \
         diagram: None,\n    \
         }};\n    \
         sitlog_robot::main_legacy(program::program(), &assets, |cli, args| {{\n        \
         legacy::task_setup(cli, args, {app_in_home}, {caption}, program::PROLOG_SOURCES)\n    \
         }})\n}}\n",
        src = app.display(),
        app_name = assets.app_name,
        world = embed(&assets.world),
        kb = embed(&assets.kb),
        app_in_home = match &legacy.app_in_home {
            Some(rel) => format!("Some({rel:?})"),
            None => "None".to_owned(),
        },
        caption = match &legacy.caption {
            Some((id, text)) => format!("Some(({id:?}, {text:?}))"),
            None => "None".to_owned(),
        },
    )
}

/// The cargo profile a package is built with (see the `[profile]` tables
/// [`write_package`] writes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Profile {
    /// `--debug`: unoptimised, the fastest to build.
    Debug,
    /// The default: optimised dependencies (built once into the cache) and
    /// the task's crate rebuilt incrementally, no LTO.
    Release,
    /// `--lto`: whole-program optimisation (fat LTO, one codegen unit), the
    /// fastest code, minutes for every build.
    Lto,
}

impl Profile {
    fn cargo_args(self) -> &'static [&'static str] {
        match self {
            Profile::Debug => &[],
            Profile::Release => &["--release"],
            Profile::Lto => &["--profile", "lto"],
        }
    }

    /// The directory of the target dir the executable is written to.
    fn dir(self) -> &'static str {
        match self {
            Profile::Debug => "debug",
            Profile::Release => "release",
            Profile::Lto => "lto",
        }
    }
}

/// Builds the package in `dir` (see [`write_package`]) and copies the
/// executable to `output`.
pub fn build_package(
    dir: &Path,
    package: &str,
    layout: &Layout,
    profile: Profile,
    output: &Path,
) -> Result<(), Error> {
    let err = |m: String| Error { messages: vec![m] };
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target_dir = layout.target.clone();
    let manifest = dir.join("Cargo.toml");
    // Offline when every dependency is already on this machine.
    let offline = Command::new(&cargo)
        .args(["fetch", "--offline", "--manifest-path"])
        .arg(&manifest)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    let mut cmd = Command::new(&cargo);
    cmd.arg("build").arg("--manifest-path").arg(&manifest);
    cmd.arg("--target-dir").arg(&target_dir);
    if offline {
        cmd.arg("--offline");
    }
    cmd.args(profile.cargo_args());
    // Progress goes to our stderr; our stdout stays clean.
    cmd.stdout(Stdio::inherit()).stderr(Stdio::inherit());
    let status = cmd
        .status()
        .map_err(|e| err(format!("cannot run cargo: {e}")))?;
    if !status.success() {
        return Err(err(format!("cargo build failed ({status})")));
    }
    let exe = target_dir
        .join(profile.dir())
        .join(format!("{package}{}", std::env::consts::EXE_SUFFIX));
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| err(format!("cannot create {}: {e}", parent.display())))?;
    }
    // Copy through a temporary file beside the output (removed on any
    // failure), renamed into place: a running executable is not overwritten
    // in place, and a failed copy leaves nothing behind.
    let copy_err = |e: std::io::Error| {
        err(format!(
            "cannot copy {} to {}: {e}",
            exe.display(),
            output.display()
        ))
    };
    let parent = match output.parent().filter(|p| !p.as_os_str().is_empty()) {
        Some(p) => p.to_path_buf(),
        None => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent)
        .map_err(|e| err(format!("cannot create {}: {e}", parent.display())))?;
    let mut tmp = tempfile::Builder::new()
        .prefix(".sitlogc-")
        .suffix(".tmp")
        .tempfile_in(&parent)
        .map_err(copy_err)?;
    let mut from = std::fs::File::open(&exe).map_err(copy_err)?;
    std::io::copy(&mut from, tmp.as_file_mut()).map_err(copy_err)?;
    let permissions = from.metadata().map_err(copy_err)?.permissions();
    std::fs::set_permissions(tmp.path(), permissions).map_err(copy_err)?;
    tmp.persist(output).map_err(|e| copy_err(e.error))?;
    Ok(())
}

/// The program's diagram as JSON (for `--view` on the compiled task).
fn diagram_json(app: &Path) -> Option<String> {
    let (checked, _) = crate::output::check_app(app, Default::default()).ok()?;
    let ir = sitlog_compiler::ir::lower(&checked.ok()?);
    let options = sitlog_compiler::diagram::Options {
        dm: None,
        main: None,
        title: sitlog_compiler::build::app_ident(app),
    };
    Some(
        sitlog_compiler::diagram::diagram(&ir, &options)
            .ok()?
            .to_json(),
    )
}
