//! `sitlogc graph`: an application drawn in the papers' notation.

use crate::args::GraphFormat;
use crate::output::checked_ir;
use std::io::Write;
use std::path::PathBuf;

pub fn graph(
    app: &std::path::Path,
    output: Option<PathBuf>,
    dm: Option<String>,
    main: Option<String>,
    format: GraphFormat,
    trace: Option<PathBuf>,
) -> u8 {
    let ir = match checked_ir(app) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let options = sitlog_compiler::diagram::Options {
        dm,
        main,
        title: sitlog_compiler::build::app_ident(app),
    };
    let diagram = match sitlog_compiler::diagram::diagram(&ir, &options) {
        Ok(d) => d,
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            return 2;
        }
    };
    let overlay = match &trace {
        None => None,
        Some(path) => {
            let text = match sitlog_syntax::read_file(path).and_then(|b| {
                sitlog_syntax::decode_owned(b).map_err(|e| {
                    std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string())
                })
            }) {
                Ok(t) => t,
                Err(e) => {
                    sitlog_runtime::errln!("error: cannot read trace {}: {e}", path.display());
                    return 2;
                }
            };
            match sitlog_graph::trace::read(&diagram, &text) {
                Ok(o) => {
                    if o.unmatched > 0 {
                        sitlog_runtime::errln!(
                            "note: {} of {} transitions of {} are not in this diagram",
                            o.unmatched,
                            o.transitions,
                            path.display()
                        );
                    }
                    Some(o)
                }
                Err(e) => {
                    sitlog_runtime::errln!("error: {}: {e}", path.display());
                    return 2;
                }
            }
        }
    };
    let text = match format {
        GraphFormat::Dot => sitlog_graph::dot::render(&diagram),
        GraphFormat::Json => diagram.to_json(),
        GraphFormat::Svg => {
            let layout = sitlog_graph::layout::layout(&diagram);
            for n in &layout.notes {
                sitlog_runtime::errln!("note: {n}");
            }
            sitlog_graph::svg::render(&diagram, &layout, overlay.as_ref())
        }
    };
    if trace.is_some() && format != GraphFormat::Svg {
        sitlog_runtime::errln!("note: --trace colours the SVG only");
    }
    match output {
        Some(path) => match std::fs::write(&path, text) {
            Ok(()) => 0,
            Err(e) => {
                sitlog_runtime::errln!("error: cannot write {}: {e}", path.display());
                2
            }
        },
        None => {
            let mut out = std::io::stdout().lock();
            match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
                Ok(()) => 0,
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
                Err(e) => {
                    sitlog_runtime::errln!("error: cannot write the diagram: {e}");
                    2
                }
            }
        }
    }
}
