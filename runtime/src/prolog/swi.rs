//! SWI-Prolog compatibility: the prelude (`prelude.pl`, consulted before the
//! application), the library predicates made visible to application code
//! ([`LIBRARIES`]), the SWI-Prolog predicates the prelude provides
//! ([`SWI_PREDICATES`]) and the engine's built-ins whose calls are renamed
//! ([`SWI_RENAMED`]), with the two look-ups the writer renames calls by.

use sitlog_syntax::Atom;

/// The prelude consulted before the application's files.
pub const PRELUDE: &str = include_str!("prelude.pl");

/// The prelude's second part, consulted after it (see `prelude_swi.pl`).
pub const PRELUDE_SWI: &str = include_str!("prelude_swi.pl");

/// Library predicates made visible to application code unless it defines
/// them itself (SWI-6 autoloads these).
pub(super) const LIBRARIES: &[(&str, &[&str])] = &[
    (
        "lists",
        &[
            "member/2",
            "select/3",
            "append/2",
            "append/3",
            "foldl/4",
            "foldl/5",
            "memberchk/2",
            "reverse/2",
            "length/2",
            "maplist/2",
            "maplist/3",
            "maplist/4",
            "maplist/5",
            "maplist/6",
            "maplist/7",
            "same_length/2",
            "nth0/3",
            "nth0/4",
            "nth1/3",
            "nth1/4",
            "sum_list/2",
            "transpose/2",
            "list_to_set/2",
            "list_max/2",
            "list_min/2",
            "permutation/2",
        ],
    ),
    (
        "between",
        &["between/3", "numlist/2", "numlist/3", "repeat/1"],
    ),
    ("format", &["format/2", "format/3", "portray_clause/1"]),
];

/// SWI-Prolog predicates the prelude provides as `'$swi_Name'`: each is
/// made visible under its own name after the application's clauses are
/// loaded, unless the application defines it or the engine already has it.
pub const SWI_PREDICATES: &[&str] = &[
    "getenv/2",
    "atomic_concat/3",
    "get0/1",
    "get0/2",
    "atom_to_chars/2",
    "flatten/2",
    "assert/1",
    "random_permutation/2",
    "last/2",
    "include/3",
    "exclude/3",
    "partition/4",
    "sumlist/2",
    "sum_list/2",
    "max_list/2",
    "min_list/2",
    "delete/3",
    "subtract/3",
    "intersection/3",
    "union/3",
    "max_member/2",
    "min_member/2",
    "atomic_list_concat/2",
    "atomic_list_concat/3",
    "concat_atom/2",
    "concat_atom/3",
    "atom_number/2",
    "upcase_atom/2",
    "downcase_atom/2",
    "nb_setval/2",
    "nb_getval/2",
    "b_setval/2",
    "b_getval/2",
    "predsort/3",
    // prelude_swi.pl
    "atom_string/2",
    "string_concat/3",
    "text_concat/3",
    "string_chars/2",
    "string_codes/2",
    "string_to_atom/2",
    "text_to_string/2",
    "string_length/2",
    "string_code/3",
    "number_string/2",
    "string_lower/2",
    "string_upper/2",
    "sub_string/5",
    "split_string/4",
    "term_string/2",
    "term_string/3",
    "sformat/2",
    "sformat/3",
    "format/1",
    "is_list/1",
    "name/2",
    "random/3",
    "random_between/3",
    "tab/1",
    "tab/2",
    "see/1",
    "seeing/1",
    "seen/0",
    "tell/1",
    "telling/1",
    "told/0",
    "file_search_path/2",
    "absolute_file_name/2",
    "absolute_file_name/3",
    "get_time/1",
    "sleep/1",
    "stamp_date_time/3",
    "date_time_stamp/2",
    "day_of_the_week/2",
    "statistics/2",
];

/// Built-ins of the engine that behave otherwise than SWI-Prolog's and
/// cannot be redefined: the application's clauses call `'$swi_Name'`
/// instead (every compound `Name(..)` of that arity in a clause is renamed,
/// and so is a closure `Name` given to `call/N`, `maplist/N`, `include/3`,
/// `exclude/3`, `partition/4`, `foldl/4..6` or `predsort/3`).
pub const SWI_RENAMED: &[(&str, usize)] = &[
    ("atom_chars", 2),
    ("compare", 3),
    ("sort", 2),
    ("msort", 2),
    ("sort", 4),
    ("keysort", 2),
    ("@<", 2),
    ("@>", 2),
    ("@=<", 2),
    ("@>=", 2),
    ("read_from_chars", 2),
    ("read_term_from_atom", 3),
    ("term_to_atom", 2),
    ("atom_to_term", 3),
    ("format", 2),
    ("format", 3),
    ("read", 1),
    ("dynamic", 1),
];

pub(super) fn swi_renamed(name: Atom, arity: usize) -> Option<Atom> {
    SWI_RENAMED
        .iter()
        .any(|&(n, a)| a == arity && n == name.as_str())
        .then(|| Atom::intern(&format!("$swi_{}", name.as_str())))
}

/// The number of arguments a meta-predicate adds to the closure it is given
/// as its first argument (or as the first of `foldl`'s), if `name/arity` is one.
pub(super) fn closure_extra(name: &str, arity: usize) -> Option<usize> {
    match (name, arity) {
        ("call", n) if n >= 2 => Some(n - 1),
        ("maplist", n) if n >= 2 => Some(n - 1),
        ("include" | "exclude", 3) => Some(1),
        ("partition", 4) => Some(1),
        ("foldl", n) if (4..=6).contains(&n) => Some(n - 1),
        ("predsort", 3) => Some(3),
        _ => None,
    }
}
