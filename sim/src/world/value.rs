//! One TOML value or table read as what a key needs: a table, an array of
//! tables, a non-empty name, a number in a range, an integer, an array of
//! `N` numbers. Each reader reports what is wrong at the value's (or the
//! table's) position and gives `None`; none of them ever panics.

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::error::Cx;
use super::model::MAX_COORDINATE;

/// A value with the byte offset it starts at.
#[derive(Clone, Debug)]
pub(super) struct At<T> {
    pub v: T,
    pub at: usize,
}

pub(super) type Val<'i> = Spanned<DeValue<'i>>;

/// A table being read: its entries, where its header is, how to name it.
pub(super) struct Tbl<'a, 'i> {
    pub t: &'a DeTable<'i>,
    pub at: usize,
    pub label: String,
}

pub(super) fn what(v: &DeValue<'_>) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

fn int_of(v: &DeValue<'_>) -> Option<Option<i64>> {
    match v {
        DeValue::Integer(i) => Some(i64::from_str_radix(i.as_str(), i.radix()).ok()),
        _ => None,
    }
}

fn num_of(v: &DeValue<'_>) -> Option<f64> {
    match v {
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => Some(n as f64),
            // Too big for i64: as a float it is out of every range anyway.
            Err(_) => Some(f64::INFINITY),
        },
        DeValue::Float(x) => Some(x.as_str().parse::<f64>().unwrap_or(f64::NAN)),
        _ => None,
    }
}

impl<'t> Cx<'t> {
    pub(super) fn table<'a, 'i>(&mut self, v: &'a Val<'i>, label: &str) -> Option<Tbl<'a, 'i>> {
        match v.get_ref() {
            DeValue::Table(t) => Some(Tbl {
                t,
                at: v.span().start,
                label: label.to_string(),
            }),
            other => {
                self.err(
                    v.span().start,
                    format!("{label} must be a table, found {}", what(other)),
                );
                None
            }
        }
    }

    /// The tables of an array of tables (`[[key]]`).
    pub(super) fn tables<'a, 'i>(&mut self, v: &'a Val<'i>, label: &str) -> Vec<Tbl<'a, 'i>> {
        match v.get_ref() {
            DeValue::Array(items) => items
                .iter()
                .filter_map(|item| self.table(item, label))
                .collect(),
            other => {
                self.err(
                    v.span().start,
                    format!(
                        "{label} must be an array of tables (write `{label}` headers), found {}",
                        what(other)
                    ),
                );
                Vec::new()
            }
        }
    }

    pub(super) fn keys(&mut self, t: &Tbl<'_, '_>, allowed: &[&str]) {
        for (k, _) in t.t.iter() {
            if !allowed.contains(&k.get_ref().as_ref()) {
                self.err(
                    k.span().start,
                    format!(
                        "unknown key `{}` in {}; known keys: {}",
                        k.get_ref(),
                        t.label,
                        allowed.join(", ")
                    ),
                );
            }
        }
    }

    pub(super) fn get<'a, 'i>(t: &Tbl<'a, 'i>, key: &str) -> Option<&'a Val<'i>> {
        t.t.get(key)
    }

    pub(super) fn req<'a, 'i>(&mut self, t: &Tbl<'a, 'i>, key: &str) -> Option<&'a Val<'i>> {
        let v = t.t.get(key);
        if v.is_none() {
            self.err(t.at, format!("missing key `{key}` in {}", t.label));
        }
        v
    }

    pub(super) fn string(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<At<String>> {
        match v.get_ref() {
            DeValue::String(s) => Some(At {
                v: s.to_string(),
                at: v.span().start,
            }),
            other => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be a string, found {}",
                        t.label,
                        what(other)
                    ),
                );
                None
            }
        }
    }

    /// A required, non-empty name.
    pub(super) fn name(&mut self, t: &Tbl<'_, '_>, key: &str) -> Option<At<String>> {
        let v = self.req(t, key)?;
        let s = self.string(t, key, v)?;
        if s.v.trim().is_empty() {
            self.err(s.at, format!("`{key}` in {} must not be empty", t.label));
            return None;
        }
        Some(s)
    }

    pub(super) fn number(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<At<f64>> {
        match num_of(v.get_ref()) {
            Some(x) => Some(At {
                v: x,
                at: v.span().start,
            }),
            None => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be a number, found {}",
                        t.label,
                        what(v.get_ref())
                    ),
                );
                None
            }
        }
    }

    /// A number that must lie in `lo..=hi` (`lo` excluded when `open_lo`).
    pub(super) fn ranged(
        &mut self,
        t: &Tbl<'_, '_>,
        key: &str,
        v: &Val<'_>,
        lo: f64,
        hi: f64,
        open_lo: bool,
    ) -> Option<f64> {
        let x = self.number(t, key, v)?;
        let ok = x.v.is_finite() && (if open_lo { x.v > lo } else { x.v >= lo }) && x.v <= hi;
        if ok {
            Some(x.v)
        } else {
            let lower = if open_lo {
                format!("greater than {lo}")
            } else {
                format!("at least {lo}")
            };
            self.err(
                x.at,
                format!(
                    "`{key}` in {} must be a finite number {lower} and at most {hi}, found {}",
                    t.label,
                    show_num(x.v)
                ),
            );
            None
        }
    }

    pub(super) fn coordinate(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<f64> {
        self.ranged(t, key, v, -MAX_COORDINATE, MAX_COORDINATE, false)
    }

    pub(super) fn integer(
        &mut self,
        t: &Tbl<'_, '_>,
        key: &str,
        v: &Val<'_>,
        lo: i64,
    ) -> Option<At<i64>> {
        match int_of(v.get_ref()) {
            Some(Some(n)) if n >= lo => Some(At {
                v: n,
                at: v.span().start,
            }),
            Some(n) => {
                let found = match n {
                    Some(n) => n.to_string(),
                    None => "a number too big".to_string(),
                };
                let least = if lo == i64::MIN {
                    String::new()
                } else {
                    format!(" of at least {lo}")
                };
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be an integer{least}, found {found}",
                        t.label
                    ),
                );
                None
            }
            None => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be an integer, found {}",
                        t.label,
                        what(v.get_ref())
                    ),
                );
                None
            }
        }
    }

    /// An array of exactly `N` numbers, each checked by `check`.
    pub(super) fn numbers<const N: usize>(
        &mut self,
        t: &Tbl<'_, '_>,
        key: &str,
        v: &Val<'_>,
        lo: f64,
        hi: f64,
        open_lo: bool,
    ) -> Option<[f64; N]> {
        let bad = |cx: &mut Self, found: String| {
            cx.err(
                v.span().start,
                format!(
                    "`{key}` in {} must be an array of {N} numbers, found {found}",
                    t.label
                ),
            );
        };
        let DeValue::Array(items) = v.get_ref() else {
            bad(self, what(v.get_ref()).to_string());
            return None;
        };
        if items.len() != N {
            bad(self, format!("{} items", items.len()));
            return None;
        }
        let mut out = [0.0; N];
        let mut ok = true;
        for (i, item) in items.iter().enumerate() {
            match self.ranged(t, key, item, lo, hi, open_lo) {
                Some(x) => out[i] = x,
                None => ok = false,
            }
        }
        ok.then_some(out)
    }
}

fn show_num(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else if x != 0.0 && (x.abs() < 1e-6 || x.abs() >= 1e15) {
        // 1e-300 as written, not three hundred digits
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}
