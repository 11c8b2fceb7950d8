//! Reads a Prolog/SitLog file with the SitLog operator table and prints every
//! clause in `writeq` style, one per line, as `swi_dump.pl` does with
//! SWI-Prolog (see tests/conformance/syntax/compare.sh). Syntax errors go to
//! stderr as `FILE:LINE:COL: message` (1-based, columns in characters).
//!
//! Usage: cargo run -p sitlog-syntax --example dump -- FILE [--stop]
//! With `--stop`, reading ends at the first syntax error (as the original
//! SitLog loader does). Clauses are read with SitLog's operator table and
//! printed with SWI-Prolog's full one (`OpTable::swi`), as SWI's `writeq` does. With `--markers`, each error is also printed to
//! stdout as `SYNTAX_ERROR LINE:COL message`, in order with the clauses.

use sitlog_syntax::{source_from_bytes, write_term, ClauseReader, OpTable, WriteOptions};
use std::io::Write;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let stop = args.iter().any(|a| a == "--stop");
    let markers = args.iter().any(|a| a == "--markers");
    let Some(path) = args.iter().find(|a| !a.starts_with("--")) else {
        eprintln!("usage: dump FILE [--stop]");
        std::process::exit(2);
    };
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(2);
        }
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let src = match source_from_bytes(&bytes) {
        Ok(src) => src,
        Err(e) => {
            let (line, col) = e.line_col_bytes(&bytes);
            eprintln!("{path}:{line}:{col}: {}", e.message);
            std::process::exit(1);
        }
    };
    // Read with SitLog's table; print with SWI's full table, as SWI's writeq does.
    let options = WriteOptions {
        quoted: true,
        ops: Some(OpTable::swi_shared()),
    };
    let mut failed = false;
    let mut reader = ClauseReader::new(src, OpTable::sitlog_shared());
    while let Some(item) = reader.next_clause() {
        match item {
            Ok(clause) => {
                let _ = writeln!(out, "{}", write_term(&clause, clause.root, options));
            }
            Err(e) => {
                failed = true;
                let _ = out.flush();
                let (line, col) = e.line_col(src);
                if markers {
                    let _ = writeln!(out, "SYNTAX_ERROR {line}:{col} {}", e.message);
                    let _ = out.flush();
                }
                eprintln!("{path}:{line}:{col}: {}", e.message);
                for (span, label) in &e.labels {
                    let (line, col) = sitlog_syntax::line_col(src, span.start as usize);
                    eprintln!("  {path}:{line}:{col}: note: {label}");
                }
                if let Some(help) = &e.help {
                    eprintln!("  help: {help}");
                }
                if stop {
                    break;
                }
            }
        }
    }
    let _ = out.flush();
    std::process::exit(i32::from(failed));
}
