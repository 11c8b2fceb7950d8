//! `sitlogc run` and `sitlogc debug`: a run of the interpreter on the
//! simulated robot or in test mode (the runner is `sitlog_robot`'s), under
//! the debugger, or reloading its sources (`--watch`, [`crate::watch`]).

use super::Strictness;
use crate::output::{checked_ir_said, deny_warnings_said};
use std::io::IsTerminal;
use std::path::PathBuf;

/// `legacy`: `Some(--sitlog-home)` under `--legacy`.
pub fn run_app(
    app: &std::path::Path,
    args: &sitlog_robot::cli::RunArgs,
    strictness: Strictness,
    legacy: Option<Option<&std::path::Path>>,
    native_kb: bool,
    debug: Option<Option<&std::path::Path>>,
    watch: bool,
) -> u8 {
    // With --format json, whatever stops the run writes the report, an
    // error found before the task runs included (issue 38: a clause too
    // deep for the engine, refused by the check, left no report).
    let json = args.format == sitlog_robot::Format::Json;
    sitlog_robot::interrupt::report_json_before_start(json);
    // An error before the task runs: `message` on stderr, and the report.
    let stop = |code: u8, message: &str| -> u8 {
        sitlog_runtime::errln!("{message}");
        stopped(json, code, message)
    };
    // The Prolog engine's start-up (most of a --legacy run's start) runs
    // on its own thread while the application is read and checked (under
    // --legacy, below: with the original's Prolog layer).
    if legacy.is_none()
        && ["user_functions.pl", "templates.pl"]
            .iter()
            .any(|f| app.join(f).exists())
    {
        sitlog_runtime::prolog::PrologFunctions::prewarm();
    }
    // The legacy profile: the original's Prolog layer from SITLOG_HOME.
    let mut before: Vec<sitlog_runtime::prolog::PrologSource> = Vec::new();
    let mut legacy_args;
    let mut args = args;
    if let Some(explicit) = legacy {
        use crate::legacy;
        legacy_args = args.clone();
        match legacy::prepare(app, explicit, &mut legacy_args, legacy::first_caption(app)) {
            Ok((_, layer)) => before = layer,
            Err(e) => return stop(2, &format!("error: {e}")),
        }
        // The engine reads the layer and asserts its clauses while the
        // application is checked.
        sitlog_runtime::prolog::PrologFunctions::prewarm_layer(
            before.clone(),
            native_kb.then(crate::legacy::native_kb),
        );
        args = &legacy_args;
    }
    let check_options = sitlog_compiler::check::CheckOptions {
        unresolved_as_warnings: strictness.allow_unresolved || legacy.is_some(),
        legacy: legacy.is_some(),
        // Only what the run can reach refuses it: a DM with errors that
        // the main DM does not name is left out, with a warning (W0232).
        task: task_name(&args.main),
        ..Default::default()
    };
    let deny = match deny_warnings_said(app, strictness.deny_warnings) {
        Ok(deny) => deny,
        Err((code, message)) => return stopped(json, code, &message),
    };
    // Denied warnings: an in_arg that does not match the pipe is an error
    // at run time too (E14), not skipped with a warning.
    let denied_args;
    if deny && args.skip_unmatched_in_arg {
        let mut a = args.clone();
        a.skip_unmatched_in_arg = false;
        denied_args = a;
        args = &denied_args;
    }
    let ir = match checked_ir_said(app, check_options, deny) {
        Ok(ir) => ir,
        Err((code, message)) => return stopped(json, code, &message),
    };
    // An output that is one of the application's files (`--trace
    // APP/main.dm`) would destroy it: refused before anything runs (issue
    // 38). Options naming each other's files are the runner's check.
    if let Some(trace) = &args.trace {
        let sources = ir
            .sources
            .files()
            .map(|(_, f)| f.path.clone())
            .filter(|p| !p.starts_with(sitlog_compiler::load::EMBEDDED));
        let side = [
            sitlog_robot::WORLD_FILE,
            sitlog_robot::ROS2_FILE,
            sitlog_robot::KB_FILE,
        ]
        .map(|name| app.join(name));
        if let Some(input) = sources.chain(side).find(|p| same_inode(p, trace)) {
            return stop(
                2,
                &format!(
                    "error: --trace {} is the application's file {}: the trace would overwrite it; give another file",
                    trace.display(),
                    input.display()
                ),
            );
        }
    }
    let mut assets = match sitlog_robot::Assets::from_app(app) {
        Ok(a) => a,
        Err(e) => return stop(e.status, &e.to_string()),
    };
    // A plain run checks its options and world file before the Prolog
    // engine starts, so a run that cannot start says so at once (issue 30),
    // its signal handling already in place (a world FIFO may block).
    let mut plain_runner = None;
    let preflighted;
    if debug.is_none() && !watch {
        let runner = runner();
        match sitlog_robot::Runner::preflight(args, &assets) {
            Ok((checked_args, checked_assets)) => {
                preflighted = checked_args;
                args = &preflighted;
                assets = checked_assets;
            }
            Err((code, message)) => return stop(code, &message),
        }
        plain_runner = Some(runner);
    }
    let mut functions = sitlog_runtime::Functions::standard();
    // The application's user_functions.pl and templates.pl (feature `prolog`).
    if let Err(errors) = sitlog_compiler::run::install_prolog_with(
        &ir,
        &mut functions,
        Default::default(),
        before,
        native_kb.then(crate::legacy::native_kb),
    ) {
        for e in &errors {
            sitlog_runtime::errln!("error: {e}");
        }
        let first = errors.first().map(|e| e.to_string()).unwrap_or_default();
        return stopped(json, 1, &first);
    }
    if args.view {
        // the live view draws the program as `sitlogc graph` does
        let options = sitlog_compiler::diagram::Options {
            dm: None,
            main: Some(args.main.split('(').next().unwrap_or("").trim().to_owned()),
            title: sitlog_compiler::build::app_ident(app),
        };
        match sitlog_compiler::diagram::diagram(&ir, &options) {
            Ok(d) => assets.diagram = Some(d.to_json()),
            Err(e) => return stop(2, &format!("error: {e}")),
        }
    }
    if watch {
        return run_watched(app, ir, functions, args, &assets, check_options);
    }
    match debug {
        // Situations run from their plans where they can (resolved once, here).
        None => {
            let resolved = sitlog_compiler::interp::Resolved::new(&ir);
            let mut runner = plain_runner.unwrap_or_else(runner);
            // --legacy in test mode: each situation type is given what the
            // original's test mode gives it.
            let test_mode = args.no_world || (args.world.is_none() && assets.world.is_none());
            if legacy.is_some() && test_mode {
                runner = runner.wrap_perception(Box::new(|inner| {
                    Box::new(sitlog_runtime::testmode::OriginalTestMode::new(inner))
                }));
            }
            runner.run(&resolved, functions, args, &assets)
        }
        Some(commands) => {
            let source = match commands {
                Some(path) => sitlog_debug::CommandSource::file(path),
                None => sitlog_debug::CommandSource::editor(),
            };
            let source = match source {
                Ok(s) => s,
                Err(e) => return stop(2, &e.to_string()),
            };
            // Plans, back to the machine's loop after each situation, so the
            // debugger sees every one.
            let resolved = sitlog_compiler::interp::Resolved::new(&ir).one_situation_per_step();
            sitlog_debug::debug(
                &resolved,
                functions,
                args,
                &assets,
                sitlog_robot::Streams::process(),
                source,
                Box::new(std::io::stdout()),
                Box::new(std::io::stderr()),
            )
        }
    }
}

/// `sitlogc run --watch`: the run over a program that reloads itself.
pub fn run_watched(
    app: &std::path::Path,
    ir: sitlog_compiler::ir::Ir,
    functions: sitlog_runtime::Functions,
    args: &sitlog_robot::cli::RunArgs,
    assets: &sitlog_robot::Assets,
    options: sitlog_compiler::check::CheckOptions,
) -> u8 {
    use crate::watch::{ReloadAware, Watched};
    let json = args.format == sitlog_robot::Format::Json;
    let files: Vec<PathBuf> = match sitlog_compiler::load::load_with(app, crate::library::library())
    {
        Ok((program, _)) => program
            .sources
            .files()
            .map(|(_, f)| f.path.clone())
            .filter(|p| !p.starts_with(sitlog_compiler::load::EMBEDDED))
            .collect(),
        Err(e) => {
            let message = format!("error: cannot read {e}");
            sitlog_runtime::errln!("{message}");
            return stopped(json, 2, &message);
        }
    };
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let messages: crate::watch::Messages =
        std::sync::Arc::new(std::sync::Mutex::new(Box::new(std::io::stderr())));
    let watched = Watched::new(ir, messages);
    if let Err(e) = watched.watch(app, &files, options, color) {
        let message = format!("error: --watch: {e}");
        sitlog_runtime::errln!("{message}");
        return stopped(json, 2, &message);
    }
    sitlog_runtime::errln!(
        "watch: watching {} ({} file(s)); edits take effect between transitions",
        app.display(),
        files.len()
    );
    let ready = watched.ready_flag();
    let wrap: sitlog_robot::PerceptionWrap =
        Box::new(move |inner| Box::new(ReloadAware::new(inner, ready)));
    runner()
        .wrap_perception(wrap)
        .run(&watched, functions, args, assets)
}

/// The name of the DM that `--main` names (`m` for `m(1)`), if it reads.
fn task_name(main: &str) -> Option<sitlog_syntax::Atom> {
    let name = main.split('(').next()?.trim();
    let name = name
        .strip_prefix('\'')
        .and_then(|n| n.strip_suffix('\''))
        .unwrap_or(name);
    (!name.is_empty()).then(|| sitlog_syntax::Atom::intern(name))
}

/// `code`, after the report of a run stopped before its task ran (with
/// `--format json`; status `error`, `message`) is written on stdout.
fn stopped(json: bool, code: u8, message: &str) -> u8 {
    if json {
        use std::io::Write as _;
        let mut out = std::io::stdout();
        let report = sitlog_runtime::report::stopped_json("error", message);
        if let Err(e) = out.write_all(report.as_bytes()).and_then(|_| out.flush()) {
            if e.kind() != std::io::ErrorKind::BrokenPipe {
                sitlog_runtime::errln!("error: cannot write the report: {e}");
                return 2;
            }
        }
    }
    code
}

/// The runner of `sitlogc run`: on the process's streams, stopped by
/// signals, and (feature `ros2`) able to run on a robot over ROS 2.
fn runner() -> sitlog_robot::Runner {
    let runner = sitlog_robot::Runner::process();
    #[cfg(feature = "ros2")]
    let runner = runner.robot(sitlog_ros::hook());
    runner
}

/// Whether `a` and `b` are the same existing file (through links, `..` and
/// hard links).
fn same_inode(a: &std::path::Path, b: &std::path::Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(ma), Ok(mb)) => {
            use std::os::unix::fs::MetadataExt;
            ma.dev() == mb.dev() && ma.ino() == mb.ino()
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        },
        _ => false,
    }
}
