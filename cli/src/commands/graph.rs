//! `sitlogc graph`: an application drawn in the papers' notation: the
//! whole program, one DM (`--dm`), the overview (`--overview`: one box per
//! DM), or the overview with a page per DM (`--out-dir`). An SVG of the
//! whole program larger than [`WHOLE_MAX`] on a side is too large to read:
//! without `--all` the overview is drawn instead, with a note.

use crate::args::GraphFormat;
use crate::output::checked_ir;
use sitlog_compiler::diagram::{self, Options};
use sitlog_compiler::ir::Ir;
use sitlog_graph::trace::Overlay;
use sitlog_graph::{Diagram, NodeKind};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Largest side, in pixels, of a whole-program SVG drawn by default.
pub const WHOLE_MAX: f64 = 4000.0;

/// What to draw and where (the options of `sitlogc graph`).
pub struct What {
    pub output: Option<PathBuf>,
    pub dm: Option<String>,
    pub main: Option<String>,
    pub format: GraphFormat,
    pub trace: Option<PathBuf>,
    /// `--coverage FILE`: the trace drawn as coverage.
    pub coverage: bool,
    pub overview: bool,
    pub out_dir: Option<PathBuf>,
    pub all: bool,
}

pub fn graph(app: &Path, what: What) -> u8 {
    let ir = match checked_ir(app) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let title = sitlog_compiler::build::app_ident(app);
    let trace = match &what.trace {
        None => None,
        Some(path) => match sitlog_syntax::read_file(path).and_then(|b| {
            sitlog_syntax::decode_owned(b)
                .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()))
        }) {
            Ok(t) => Some((path.as_path(), t)),
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read trace {}: {e}", path.display());
                return 2;
            }
        },
    };
    if let Some(dir) = &what.out_dir {
        return pages(&ir, &what, title, dir, trace);
    }
    let options = Options {
        dm: what.dm.clone(),
        main: what.main.clone(),
        title: title.clone(),
    };
    let text = if what.overview {
        if trace.is_some() {
            sitlog_runtime::errln!(
                "note: --trace colours situations and arcs: not drawn in the overview"
            );
        }
        render(&diagram::overview(&ir, &options), what.format, None)
    } else {
        let diagram = match diagram::diagram(&ir, &options) {
            Ok(d) => d,
            Err(e) => {
                sitlog_runtime::errln!("error: {e}");
                return 2;
            }
        };
        let overlay = match &trace {
            None => None,
            Some((path, text)) => match colours(&diagram, path, text, true, what.coverage) {
                Ok(o) => Some(o),
                Err(code) => return code,
            },
        };
        if trace.is_some() && what.format != GraphFormat::Svg {
            sitlog_runtime::errln!("note: --trace colours the SVG only");
        }
        match what.format {
            GraphFormat::Svg => {
                let layout = sitlog_graph::layout::layout(&diagram);
                let big = layout.width.max(layout.height) > WHOLE_MAX;
                if big && what.dm.is_none() && !what.all {
                    sitlog_runtime::errln!(
                        "note: all {} DMs in one picture would be {}×{} px, too large to read: drawn as the overview (one box per DM); `--out-dir DIR` adds a page per DM, `--all` draws them in one picture",
                        diagram.dms.len(),
                        layout.width,
                        layout.height
                    );
                    render(&diagram::overview(&ir, &options), GraphFormat::Svg, None)
                } else {
                    for n in &layout.notes {
                        sitlog_runtime::errln!("note: {n}");
                    }
                    sitlog_graph::svg::render(&diagram, &layout, overlay.as_ref())
                }
            }
            format => render(&diagram, format, None),
        }
    };
    match &what.output {
        Some(path) => write_file(path, &text),
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

/// `d` in `format` (an SVG laid out here, its layout notes on stderr).
fn render(d: &Diagram, format: GraphFormat, overlay: Option<&Overlay>) -> String {
    match format {
        GraphFormat::Dot => sitlog_graph::dot::render(d),
        GraphFormat::Json => d.to_json(),
        GraphFormat::Svg => {
            let layout = sitlog_graph::layout::layout(d);
            for n in &layout.notes {
                sitlog_runtime::errln!("note: {n}");
            }
            sitlog_graph::svg::render(d, &layout, overlay)
        }
    }
}

/// A recorded run read against `d`; with `notes`, says how many of its
/// transitions are not in the drawing; with `coverage`, drawn as coverage.
fn colours(
    d: &Diagram,
    path: &Path,
    text: &str,
    notes: bool,
    coverage: bool,
) -> Result<Overlay, u8> {
    match sitlog_graph::trace::read(d, text) {
        Ok(mut o) => {
            o.coverage = coverage;
            if notes && o.unmatched > 0 {
                sitlog_runtime::errln!(
                    "note: {} of {} transitions of {} are not in this diagram",
                    o.unmatched,
                    o.transitions,
                    path.display()
                );
            }
            Ok(o)
        }
        Err(e) => {
            sitlog_runtime::errln!("error: {}: {e}", path.display());
            Err(2)
        }
    }
}

fn write_file(path: &Path, text: &str) -> u8 {
    match std::fs::write(path, text) {
        Ok(()) => 0,
        Err(e) => {
            sitlog_runtime::errln!("error: cannot write {}: {e}", path.display());
            2
        }
    }
}

/// The page of each DM: its name with what a file name cannot hold
/// replaced by `_`, numbered when two DMs would share one (`index` is the
/// overview's). `None` for a DM whose name an earlier DM has (calls by
/// name reach the first, which has the page).
fn page_names(ir: &Ir) -> Vec<Option<String>> {
    let mut taken = vec!["index".to_owned()];
    let mut names = Vec::new();
    for (i, dm) in ir.dms.iter().enumerate() {
        if ir.dms[..i].iter().any(|d| d.name == dm.name) {
            names.push(None);
            continue;
        }
        let base: String = dm
            .name
            .as_str()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let base = if base.is_empty() {
            "dm".to_owned()
        } else {
            base
        };
        let mut name = base.clone();
        let mut k = 2;
        while taken.iter().any(|t| t.eq_ignore_ascii_case(&name)) {
            name = format!("{base}_{k}");
            k += 1;
        }
        taken.push(name.clone());
        names.push(Some(name));
    }
    names
}

/// `--out-dir DIR`: the overview (`index.EXT`, and `index.html` for SVG)
/// and one page per DM (`NAME.EXT`), each coloured by the trace if any.
fn pages(ir: &Ir, what: &What, title: String, dir: &Path, trace: Option<(&Path, String)>) -> u8 {
    if let Err(e) = std::fs::create_dir_all(dir) {
        sitlog_runtime::errln!("error: cannot make {}: {e}", dir.display());
        return 2;
    }
    let ext = match what.format {
        GraphFormat::Svg => "svg",
        GraphFormat::Dot => "dot",
        GraphFormat::Json => "json",
    };
    let names = page_names(ir);
    let page_of = |i: usize| -> Option<String> {
        let name = ir
            .dms
            .get(i)
            .and_then(|dm| ir.dm_by_name(dm.name))
            .and_then(|first| names[first as usize].as_ref())?;
        Some(format!("{name}.{ext}"))
    };
    let options = Options {
        dm: None,
        main: what.main.clone(),
        title: title.clone(),
    };
    let mut index = diagram::overview(ir, &options);
    for n in index.externals.iter_mut() {
        if let Some(i) = n.id.strip_prefix('d').and_then(|i| i.parse().ok()) {
            n.link = page_of(i);
        }
    }
    let code = write_file(
        &dir.join(format!("index.{ext}")),
        &render(&index, what.format, None),
    );
    if code != 0 {
        return code;
    }
    let mut written = Vec::new();
    for (i, dm) in ir.dms.iter().enumerate() {
        let Some(name) = &names[i] else { continue };
        let options = Options {
            dm: Some(dm.name.as_str().to_owned()),
            main: what.main.clone(),
            title: title.clone(),
        };
        let mut d = match diagram::diagram(ir, &options) {
            Ok(d) => d,
            Err(e) => {
                sitlog_runtime::errln!("error: {e}");
                return 2;
            }
        };
        for n in d.externals.iter_mut() {
            if n.kind == NodeKind::ExternalDm {
                if let Some(k) = n.id.strip_prefix('x').and_then(|k| k.parse().ok()) {
                    n.link = page_of(k);
                }
            }
        }
        let overlay = match &trace {
            Some((path, text)) => match colours(&d, path, text, false, what.coverage) {
                Ok(o) => Some(o),
                Err(code) => return code,
            },
            None => None,
        };
        let code = write_file(
            &dir.join(format!("{name}.{ext}")),
            &render(&d, what.format, overlay.as_ref()),
        );
        if code != 0 {
            return code;
        }
        written.push((name.clone(), d.dms[0].name.clone()));
    }
    if what.format == GraphFormat::Svg {
        let code = write_file(&dir.join("index.html"), &html(&title, &written));
        if code != 0 {
            return code;
        }
    }
    sitlog_runtime::errln!(
        "wrote {}: the overview (index.{ext}) and {} DM page(s)",
        dir.display(),
        written.len()
    );
    0
}

/// `index.html`: the overview (its boxes link to the pages) and the list
/// of pages.
fn html(title: &str, pages: &[(String, String)]) -> String {
    let esc = sitlog_graph::svg::esc;
    let mut s = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{t}</title></head>\n<body style=\"font-family: sans-serif\">\n<h1>{t}</h1>\n<p>One box per DM; click a box for the DM's page.</p>\n<object data=\"index.svg\" type=\"image/svg+xml\" style=\"max-width: 100%\"></object>\n<h2>DMs</h2>\n<ul>\n",
        t = esc(title)
    );
    for (file, name) in pages {
        s.push_str(&format!(
            "<li><a href=\"{}.svg\">{}</a></li>\n",
            esc(file),
            esc(name)
        ));
    }
    s.push_str("</ul>\n</body></html>\n");
    s
}
