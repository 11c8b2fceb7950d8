//! `sitlogc build`: an application compiled to one executable
//! ([`crate::package`]), its generated Rust (`--emit rust`), or what the typed
//! MIR and native code are (`--explain-types`).

use super::Strictness;
use crate::args::Emit;
use crate::output::{checked_ir, checked_ir_strict, deny_warnings, with_world, write_stdout};
use std::path::PathBuf;

pub fn explain_types_of(app: &std::path::Path) -> u8 {
    match checked_ir(app) {
        Ok(ir) => write_stdout(
            &sitlog_compiler::codegen::explain_types(&ir),
            "the type listing",
        ),
        Err(code) => code,
    }
}

/// `legacy`: `Some(--sitlog-home)` under `--legacy`.
#[allow(clippy::too_many_arguments)] // the command's options, as `run_app` takes them
pub fn build_app(
    app: &std::path::Path,
    output: Option<PathBuf>,
    profile: crate::package::Profile,
    emit: Option<Emit>,
    strictness: Strictness,
    debugger: bool,
    ros2: bool,
    legacy: Option<Option<&std::path::Path>>,
) -> u8 {
    use crate::package;
    use sitlog_compiler::build;
    // `--legacy`: the original's rules, as `sitlogc run --legacy` checks
    // the application; its tree is found now only to place the application
    // in it (the task reads the tree's Prolog layer when it starts).
    let legacy = match legacy {
        Some(explicit) => match crate::legacy::find_home(app, explicit) {
            Ok(home) => {
                let canonical = |p: &std::path::Path| {
                    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
                };
                let app_in_home = canonical(app)
                    .strip_prefix(canonical(&home))
                    .ok()
                    .map(|rel| rel.display().to_string());
                Some(package::Legacy {
                    app_in_home,
                    caption: crate::legacy::first_caption(app),
                })
            }
            Err(e) => {
                sitlog_runtime::errln!("error: {e}");
                return 2;
            }
        },
        None => None,
    };
    let options = with_world(sitlog_compiler::check::CheckOptions {
        unresolved_as_warnings: strictness.allow_unresolved || legacy.is_some(),
        legacy: legacy.is_some(),
        ..Default::default()
    });
    let deny = match deny_warnings(app, strictness.deny_warnings) {
        Ok(deny) => deny,
        Err(code) => return code,
    };
    if let Err(code) = checked_ir_strict(app, options, deny) {
        return code;
    }
    let compiled =
        match build::generate_checked(app, &app.display().to_string(), Default::default(), options)
        {
            Ok(c) => c,
            Err(e) => {
                sitlog_runtime::errln!("error: {e}");
                return 1;
            }
        };
    if emit == Some(Emit::Rust) {
        let text = compiled.to_file_string();
        return match output {
            Some(path) => match build::write_if_changed(&path, &text) {
                Ok(_) => 0,
                Err(e) => {
                    sitlog_runtime::errln!("error: cannot write {}: {e}", path.display());
                    2
                }
            },
            None => write_stdout(&text, "the generated code"),
        };
    }
    let output = match output_file(app, output) {
        Ok(o) => o,
        Err(message) => {
            sitlog_runtime::errln!("error: {message}");
            return 2;
        }
    };
    let layout = match package::Layout::user() {
        Ok(l) => l,
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            return 2;
        }
    };
    let built = package::write_package(&compiled, app, &layout, debugger, ros2, legacy.as_ref())
        .and_then(|(dir, name)| {
            sitlog_runtime::errln!("sitlogc: building {} in {}", name, dir.display());
            package::build_package(&dir, &name, &layout, profile, &output)
        });
    match built {
        Ok(()) => {
            sitlog_runtime::errln!("sitlogc: wrote {}", output.display());
            0
        }
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            2
        }
    }
}

/// Where `build` writes the executable: `-o FILE`, else a file named after
/// the application (its directory's real name, or the DM file's stem) in
/// the current directory. A directory there (the application itself when
/// building from beside it) is refused before anything is built, as
/// `go build` does, rather than writing somewhere the user did not ask.
pub fn output_file(app: &std::path::Path, output: Option<PathBuf>) -> Result<PathBuf, String> {
    let given = output.is_some();
    let output = output.unwrap_or_else(|| PathBuf::from(sitlog_robot::app_name(app)));
    if output.is_dir() {
        let o = output.display();
        return Err(if given {
            format!("cannot write the executable to `{o}`: it is a directory; give a file name with -o FILE")
        } else {
            format!(
                "the default output `{o}` is a directory (the application itself, when you build from beside it); \
                 name the executable with -o FILE, e.g. `sitlogc build {} -o {o}-task`",
                app.display()
            )
        });
    }
    Ok(output)
}
