//! Names and literals in generated code: atoms to unique `snake_case` and
//! `CamelCase` identifiers (raw identifiers for keywords), and integer and
//! float literals that round-trip exactly.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

pub(super) const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

/// `snake_case` identifier text for an atom (not yet made unique).
pub(super) fn snake(text: &str) -> String {
    let mut s = String::new();
    let wordy = text.chars().any(|c| c.is_ascii_alphanumeric());
    for c in text.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if c == '_' || (wordy && (c == ' ' || c == '-')) {
            s.push('_');
        } else {
            let name = match c {
                '[' | ']' => "nil",
                '.' => "dot",
                '-' => "minus",
                ' ' => "space",
                ',' => "comma",
                '|' => "bar",
                '+' => "plus",
                '*' => "star",
                '/' => "slash",
                '=' => "eq",
                '<' => "lt",
                '>' => "gt",
                ':' => "colon",
                ';' => "semi",
                '$' => "dollar",
                '\\' => "bslash",
                '{' | '}' => "curly",
                '!' => "bang",
                '?' => "q",
                '@' => "at",
                '#' => "hash",
                '&' => "amp",
                '^' => "caret",
                '~' => "tilde",
                '\'' => "quote",
                _ => "u",
            };
            if !s.is_empty() && !s.ends_with('_') {
                s.push('_');
            }
            s.push_str(name);
            s.push('_');
        }
    }
    let s = s.trim_matches('_').to_owned();
    let mut s = if s.is_empty() { "atom".to_owned() } else { s };
    // `[]` is common enough for a short name.
    if text == "[]" {
        s = "nil".to_owned();
    }
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}

/// `CamelCase` identifier text.
pub(super) fn camel(text: &str) -> String {
    let mut out = String::new();
    for part in snake(text).split('_').filter(|p| !p.is_empty()) {
        let mut cs = part.chars();
        if let Some(c) = cs.next() {
            out.push(c.to_ascii_uppercase());
            out.extend(cs);
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, 'S');
    }
    out
}

/// Makes names unique in order of request (`x`, `x_2`, `x_3`, ...).
#[derive(Default)]
pub(super) struct Namer {
    used: HashMap<String, usize>,
}

impl Namer {
    pub(super) fn fresh(&mut self, base: String) -> String {
        let n = self.used.entry(base.clone()).or_insert(0);
        *n += 1;
        if *n == 1 {
            base
        } else {
            let name = format!("{base}_{n}");
            // A generated name may itself collide with a later base name.
            self.fresh(name)
        }
    }
}

pub(super) fn ident(text: &str) -> Ident {
    if KEYWORDS.contains(&text) {
        if matches!(text, "self" | "Self" | "super" | "crate") {
            format_ident!("{}_", text)
        } else {
            Ident::new_raw(text, Span::call_site())
        }
    } else {
        Ident::new(text, Span::call_site())
    }
}

/// An atom as writeq would quote it (for docs only).
pub(super) fn quote_atom(text: &str) -> String {
    let plain = text.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain || text == "[]" {
        text.to_owned()
    } else {
        format!("'{}'", text.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

pub(super) fn int_expr(i: i64) -> TokenStream {
    let term = quote!(Term);
    if i == i64::MIN {
        quote!(#term::int(i64::MIN))
    } else if i < 0 {
        let lit = Literal::i64_unsuffixed(-i);
        quote!(#term::int(-#lit))
    } else {
        let lit = Literal::i64_unsuffixed(i);
        quote!(#term::int(#lit))
    }
}

pub(super) fn float_expr(f: f64) -> TokenStream {
    let term = quote!(Term);
    if f.is_finite() && f.is_sign_positive() && f != 0.0 {
        let lit = Literal::f64_unsuffixed(f);
        quote!(#term::float(#lit))
    } else if f.is_finite() && f.is_sign_negative() && f != 0.0 {
        let lit = Literal::f64_unsuffixed(-f);
        quote!(#term::float(-#lit))
    } else {
        let bits = Literal::u64_suffixed(f.to_bits());
        quote!(#term::float(f64::from_bits(#bits)))
    }
}
