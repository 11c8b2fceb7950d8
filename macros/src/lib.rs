//! `include_dm!`: a thin proc-macro layer over `sitlog-compiler`.
//!
//! ```ignore
//! mod countdown {
//!     sitlog_macros::include_dm!("dms/examples/countdown");
//! }
//! let (outcome, store) = countdown::run("main", None, options, functions, &mut perception, &mut actions, None)?;
//! ```
//!
//! The path (an application directory or a DM file) is relative to the
//! invoking crate's `Cargo.toml` (or to `$SITLOG_DM_ROOT` when that is set:
//! the trybuild tests use it, since their crate lives in the target dir). The macro expands to the items
//! `sitlog_compiler::codegen` generates (`Program`, `program()`, `run`,
//! `main_with`, one `dm_<name>` module per DM), plus one
//! `include_bytes!` per source file read, so that Cargo rebuilds when a DM
//! changes. Errors in the DM sources become `compile_error!`s naming
//! `file.dm:line:col` and showing the source line. The invoking crate needs
//! `sitlog-runtime` as a dependency. `include_dm!("path", untyped)` keeps
//! every value a term (no native code; for comparisons).

use proc_macro::TokenStream;
use quote::quote;
use std::path::PathBuf;

#[proc_macro]
pub fn include_dm(input: TokenStream) -> TokenStream {
    // `"path"`, `"path", untyped` (every value a term: for comparisons) or
    // `"path", held` (evaluated DM calls pushed natively,
    // `codegen::Options::held_calls`: the default, the flag kept for the
    // tests that name it).
    let parser = |input: syn::parse::ParseStream| -> syn::Result<(syn::LitStr, Option<String>)> {
        let lit: syn::LitStr = input.parse()?;
        if input.is_empty() {
            return Ok((lit, None));
        }
        input.parse::<syn::Token![,]>()?;
        let flag: syn::Ident = input.parse()?;
        if flag != "untyped" && flag != "held" {
            return Err(syn::Error::new(flag.span(), "expected `untyped` or `held`"));
        }
        Ok((lit, Some(flag.to_string())))
    };
    let (lit, flag) = match syn::parse::Parser::parse(parser, input) {
        Ok(l) => l,
        Err(e) => {
            let msg =
                "include_dm! takes one string literal: the path of a SitLog application or DM file";
            return syn::Error::new(e.span(), msg).to_compile_error().into();
        }
    };
    let options = sitlog_compiler::codegen::Options {
        typed: flag.as_deref() != Some("untyped"),
        // On by default (`held` says so, kept for the tests that name it).
        held_calls: true,
    };
    let rel = lit.value();
    let base = std::env::var_os("SITLOG_DM_ROOT")
        .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
        .map(PathBuf::from)
        .unwrap_or_default();
    let path = base.join(&rel);
    match sitlog_compiler::build::generate_with(&path, &rel, options) {
        Ok(compiled) => {
            let tokens = compiled.tokens;
            let files = compiled.files.iter().map(|f| {
                let f = f.canonicalize().unwrap_or_else(|_| f.clone());
                let s = f.display().to_string();
                quote!(
                    const _: &[u8] = ::core::include_bytes!(#s);
                )
            });
            quote!(#tokens #(#files)*).into()
        }
        Err(e) => {
            let msg = format!("SitLog program `{rel}` does not compile:\n{e}");
            syn::Error::new(lit.span(), msg).to_compile_error().into()
        }
    }
}
