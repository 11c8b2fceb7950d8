//! `sitlogc replay`: a recorded run (`--trace`) replayed or compared.

/// `sitlogc replay`.
pub fn replay(
    trace: &std::path::Path,
    diff: Option<&std::path::Path>,
    commands: Option<&std::path::Path>,
) -> u8 {
    let read = |path| match sitlog_debug::Trace::read(path) {
        Ok(t) => Ok(t),
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            Err(2)
        }
    };
    let trace = match read(trace) {
        Ok(t) => t,
        Err(code) => return code,
    };
    if let Some(other) = diff {
        let other = match read(other) {
            Ok(t) => t,
            Err(code) => return code,
        };
        return match sitlog_debug::diff(&trace, &other) {
            None => crate::output::write_stdout(
                &format!(
                    "the recordings are the same ({} transitions)\n",
                    trace.records.len()
                ),
                "the comparison",
            ),
            Some(text) => match crate::output::write_stdout(&text, "the differences") {
                0 => 1,
                code => code,
            },
        };
    }
    let source = match commands {
        Some(path) => sitlog_debug::CommandSource::file(path),
        None => sitlog_debug::CommandSource::editor(),
    };
    match source {
        Ok(source) => sitlog_debug::replay(
            &trace,
            source,
            &mut std::io::stdout(),
            &mut std::io::stderr(),
        ),
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            2
        }
    }
}
