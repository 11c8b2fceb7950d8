//! Workloads of shapes (c) and (d) of issue 37 written from the issue's
//! text (`tests/typed/shapes/c_*`, `d_*` of helper `ngen11`), each run three
//! ways for counting instructions with callgrind: the compiled task
//! (`include_dm!`, native code where the compiler gives it), the
//! interpreter (`sitlogc run`'s plans) and a hand-written Rust machine doing
//! the same work (atoms as an interned index, lists as slices, frames on an
//! explicit stack, `black_box` where `benches/benches/compiled.rs` puts it).
//!
//! `shapes_prof WORKLOAD compiled|interp|hand ROUNDS [PLACES]` prints the
//! transitions; `shapes_prof check` runs every workload all three ways at
//! a small size and asserts that they make the same transitions.
//! Instructions per transition: the difference of two callgrind runs of
//! different lengths over the difference of their transitions
//! (docs/guide/performance.md, "workloads of the same shapes, not ours").

use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::machine::{Options, Outcome};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{app, Functions, Store};
use std::hint::black_box;
use std::path::Path;

mod c_limit_inarg_echo {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_limit_inarg_echo");
}
mod c_counter_param {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_counter_param");
}
mod c_outarg_cond {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_outarg_cond");
}
mod c_deeper_echo {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_deeper_echo");
}
mod d_target_in_id {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_target_in_id");
}
mod d_id_shares_param {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_id_shares_param");
}
mod d_local_places {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_local_places");
}
mod d_const_ints {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_const_ints");
}
mod d_built_list {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_built_list");
}
mod d_acc_seen {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_acc_seen");
}
mod d_found_rest {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_found_rest");
}
mod d_shelf_pairs {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_shelf_pairs");
}
// Helper `ngen12`'s (session 11).
mod c_first_param {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_first_param");
}
mod c_float_limit {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_float_limit");
}
mod d_walk_first_param {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_walk_first_param");
}
mod d_target_matched_in_id {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_target_matched_in_id");
}
mod c_global_count {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_global_count");
}
mod d_compare_fn {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_compare_fn");
}
// Helper `nshape13`'s (session 12).
mod c_pipe_pair {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_pipe_pair");
}
mod c_final_by_inarg {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_final_by_inarg");
}
mod c_local_limit_hop {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_local_limit_hop");
}
mod d_ints_inarg_threshold {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_ints_inarg_threshold");
}
mod d_place_records {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_place_records");
}
mod d_confirm_found {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_confirm_found");
}
mod d_appended_list {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_appended_list");
}
// Helper `ngen13`'s (session 12).
mod c_outarg_apply {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_outarg_apply");
}
// Helper `nglob13`'s (session 12): globals.
mod c_global_flag {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_global_flag");
}
mod d_global_visited {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_global_visited");
}
// Helper `nout14`'s (session 13): an evaluated out_arg in a walk.
mod d_outarg_when {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_outarg_when");
}
// Ours (`benches/dms`), for comparing the compiled and interpreted runs
// of a change with the benchmarks' (no hand-written way here: see
// `benches/benches/compiled.rs`).
mod echo_calls {
    sitlog_macros::include_dm!("dms/echo_calls");
}
mod list_search {
    sitlog_macros::include_dm!("dms/list_search");
}

/// Runs a program with `--history none`'s options; its transitions.
fn run_piped<A: app::App>(app: &A, main: &str, in_arg: Option<&str>) -> u64 {
    run_fns(app, main, in_arg, Functions::standard())
}

/// [`run`] with the Prolog user functions of workload `name` installed
/// (`d_compare_fn`'s `same_place/2`), both ways alike.
fn run_prolog<A: app::App>(app: &A, main: &str, name: &str) -> u64 {
    let mut f = Functions::standard();
    sitlog_compiler::run::install_prolog(&interpreter(name), &mut f, Default::default())
        .expect("the workload's Prolog loads");
    run_fns(app, main, None, f)
}

fn run_fns<A: app::App>(app: &A, main: &str, in_arg: Option<&str>, functions: Functions) -> u64 {
    let mut perception = ScriptPerception::new("script", String::new());
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let options = Options {
        keep_history: false,
        ..Options::default()
    };
    let (outcome, _store): (Outcome, Store) = app::run(
        app,
        main,
        in_arg,
        options,
        functions,
        &mut perception,
        &mut actions,
        None,
    )
    .expect("runs");
    assert!(outcome.result.is_ok(), "{main}: {:?}", outcome.result);
    outcome.transitions
}

fn interpreter(dir: &str) -> Ir {
    let root = match dir {
        "echo_calls" | "list_search" => "dms",
        _ => "../tests/typed/shapes",
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(root).join(dir);
    let (checked, _) = sitlog_compiler::check_path(&dir).expect("readable");
    sitlog_compiler::ir::lower(&checked.expect("checks"))
}

/// An atom of the hand-written machines: an interned index.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct Sym(u32);

/// (c) with the limit in the pipe: `depth` 1 (the callee hands the pipe
/// back) or 2 (a DM between, passing it through); the count in the
/// caller's id, a local or the callee's parameter (all an `i64` here).
/// `start`: the caller's first situation setting the pipe.
fn hand_echo(limit: i64, depth: u32, cond_out: bool) -> u64 {
    hand_echo_as(limit, depth, cond_out, false)
}

/// [`hand_echo`] with the limit a float (`float`: the count, an int,
/// compared with it as the machine compares an int with a float).
fn hand_echo_as(limit: i64, depth: u32, cond_out: bool, float: bool) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask,
        Over,
        Hop(bool),
        Take,
        Back,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut n, mut transitions) = (0i64, 0i64, 0u64);
    let mut pipe_f = 0f64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                pipe = black_box(limit);
                pipe_f = black_box(limit as f64);
                *top = Frame::Ask;
            }
            Frame::Ask => {
                let callee = if depth == 2 {
                    Frame::Hop(false)
                } else {
                    Frame::Take
                };
                stack.push(callee);
            }
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
            Frame::Hop(false) => {
                *top = Frame::Hop(true);
                stack.push(Frame::Take);
            }
            Frame::Take => {
                transitions += 1;
                // in_arg X, out_arg X (or the conditional on X).
                pipe = black_box(if cond_out && pipe <= 0 { 1 } else { pipe });
                *top = Frame::Back;
            }
            Frame::Back | Frame::Hop(true) => {
                transitions += 1;
                stack.pop();
                if depth == 2 {
                    if let Some(Frame::Hop(true)) = stack.last() {
                        // `hop`'s recursive situation concludes, its final.
                        transitions += 2;
                        stack.pop();
                    }
                }
                transitions += 1;
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    let more = if float { (n as f64) < pipe_f } else { n < pipe };
                    *m = if more { Frame::Ask } else { Frame::Over };
                }
            }
        }
    }
    transitions
}

/// What a walk's final hands back.
#[derive(Clone, Copy)]
enum Exit<'a, T> {
    Found(T),
    FoundRest(T, &'a [T]),
    NotFound,
}

/// (d): `rounds` calls of a walk over `items` for `target`, the list a
/// slice, the element compared by `==`; `start`: the caller's first
/// situation (one transition); `rest`: the final hands back the rest.
fn hand_walk<T: Copy + PartialEq>(
    rounds: i64,
    items: &[T],
    target: T,
    start: bool,
    rest: bool,
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a, T> {
        Round,
        Stop,
        Begin,
        Try(&'a [T]),
        Final(Exit<'a, T>),
    }
    let mut stack: Vec<Frame<T>> = vec![Frame::Round];
    let (mut n, mut transitions) = (0i64, u64::from(start));
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items);
            }
            Frame::Try([]) => {
                transitions += 1;
                *top = Frame::Final(Exit::NotFound);
            }
            Frame::Try([p, ps @ ..]) => {
                transitions += 1;
                *top = if *p == target {
                    Frame::Final(if rest {
                        Exit::FoundRest(*p, ps)
                    } else {
                        Exit::Found(*p)
                    })
                } else {
                    Frame::Try(ps)
                };
            }
            Frame::Final(exit) => {
                transitions += 1;
                // The caller's exit arc binds what the final hands back.
                match exit {
                    Exit::Found(p) => black_box(Some(p)),
                    Exit::FoundRest(p, r) => {
                        black_box(r);
                        black_box(Some(p))
                    }
                    Exit::NotFound => black_box(None),
                };
                stack.pop();
                transitions += 1;
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// (d) with an accumulator: the places passed kept in a `Vec` (reused
/// from round to round), handed back by the final.
fn hand_walk_seen(rounds: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Look(&'a [Sym]),
        Found(Sym),
        NotFound,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let mut seen: Vec<Sym> = Vec::with_capacity(items.len());
    let (mut n, mut transitions) = (0i64, 1u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                seen.clear();
                *top = Frame::Look(items);
            }
            Frame::Look([]) => {
                transitions += 1;
                *top = Frame::NotFound;
            }
            Frame::Look([p, ps @ ..]) => {
                transitions += 1;
                *top = if *p == target {
                    Frame::Found(*p)
                } else {
                    seen.push(*p);
                    Frame::Look(ps)
                };
            }
            Frame::Found(_) | Frame::NotFound => {
                transitions += 1;
                let found = match *top {
                    Frame::Found(p) => Some(p),
                    _ => None,
                };
                black_box((found, &seen));
                stack.pop();
                transitions += 1;
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// A list of `len` places `p0..`, as text, and as symbols.
fn places(len: usize) -> (String, Vec<Sym>) {
    let names: Vec<String> = (0..len).map(|i| format!("p{i}")).collect();
    (
        format!("[{}]", names.join(",")),
        (0..len as u32).map(Sym).collect(),
    )
}

const INTS: [i64; 8] = [12, 7, 33, 41, 5, 18, 29, 64];

/// Runs workload `name` one way; its transitions.
fn one(name: &str, way: &str, n: i64, len: usize) -> u64 {
    let (list, syms) = places(len);
    let last = format!("p{}", len - 1);
    let lsym = Sym(len as u32 - 1);
    let pairs: Vec<String> = (0..len).map(|i| format!("p{i}-s{}", i % 5)).collect();
    let pairs_text = format!("[{}]", pairs.join(","));
    let sym_pairs: Vec<(Sym, Sym)> = (0..len as u32).map(|i| (Sym(i), Sym(i % 5))).collect();
    let main = match name {
        "c_limit_inarg_echo" | "c_counter_param" | "c_outarg_cond" | "c_deeper_echo" => {
            format!("relay({n})")
        }
        "c_first_param" => format!("relay({n})"),
        "c_float_limit" => format!("relay({n}.0)"),
        "c_outarg_apply" => format!("relay({n})"),
        "c_global_count" => format!("relay({n})"),
        "c_global_flag" => format!("boss({n})"),
        // The budget: `n` rounds of `len` visits (the target the last).
        "d_global_visited" => format!("hunt({}, {list}, {last})", n * len as i64),
        "d_target_in_id"
        | "d_id_shares_param"
        | "d_walk_first_param"
        | "d_target_matched_in_id"
        | "d_compare_fn"
        | "d_outarg_when" => format!("hunt({n}, {list}, {last})"),
        "d_local_places" => format!("tour({n}, cellar)"),
        "d_const_ints" => format!("drill({n}, 64)"),
        "d_built_list" => format!("patrol({n}, {list}, p0)"),
        "d_acc_seen" => format!("survey({n}, {list}, {last})"),
        "d_found_rest" => format!("visit({n}, {list}, {last})"),
        "d_shelf_pairs" => format!("stock({n}, {pairs_text}, {last})"),
        "list_search" => format!("main({n}, {list}, {last})"),
        "c_pipe_pair" | "c_final_by_inarg" | "c_local_limit_hop" => format!("relay({n})"),
        "d_ints_inarg_threshold" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("scan({n}, [{}], {})", ints.join(","), len - 2)
        }
        "d_place_records" => {
            let recs: Vec<String> = (0..len).map(|i| format!("place(p{i},{i})")).collect();
            format!("fetch({n}, [{}], {})", recs.join(","), len - 1)
        }
        "d_confirm_found" => format!("hunt({n}, {list}, {last})"),
        "d_appended_list" => format!("route({n}, [{}], dock)", {
            let names: Vec<String> = (0..len - 1).map(|i| format!("p{i}")).collect();
            names.join(",")
        }),
        "echo_calls" => {
            let n = n.to_string();
            return match way {
                "compiled" => run_piped(echo_calls::program(), "main", Some(&n)),
                "interp" => run_piped(&Resolved::new(&interpreter(name)), "main", Some(&n)),
                _ => panic!("echo_calls: compiled or interp"),
            };
        }
        _ => panic!("no workload {name}"),
    };
    macro_rules! ways {
        ($m:ident) => {
            match way {
                "compiled" => run_prolog($m::program(), &main, name),
                "interp" => run_prolog(&Resolved::new(&interpreter(name)), &main, name),
                _ => unreachable!(),
            }
        };
    }
    if way == "hand" {
        let n = black_box(n);
        return match name {
            "c_limit_inarg_echo" | "c_counter_param" | "c_first_param" => hand_echo(n, 1, false),
            "c_float_limit" => hand_echo_as(n, 1, false, true),
            "c_outarg_apply" => hand_succ(n),
            // No first situation setting the pipe: one transition less.
            "c_global_count" => hand_echo(n, 1, false) - 1,
            "c_outarg_cond" => hand_echo(n, 1, true),
            "c_global_flag" => hand_flag(n),
            "d_global_visited" => {
                hand_walk_visited(n * len as i64, black_box(&syms), black_box(lsym))
            }
            "c_deeper_echo" => hand_echo(n, 2, false),
            "d_target_in_id"
            | "d_id_shares_param"
            | "d_walk_first_param"
            | "d_target_matched_in_id"
            | "d_compare_fn" => hand_walk(n, black_box(&syms), black_box(lsym), true, false),
            "d_outarg_when" => hand_walk_flag(n, black_box(&syms), black_box(lsym)),
            "d_local_places" => {
                hand_walk(n, black_box(&syms[..8]), black_box(Sym(7)), false, false)
            }
            "d_const_ints" => hand_walk(n, black_box(&INTS), black_box(64), true, false),
            "d_built_list" => {
                let reversed: Vec<Sym> = syms.iter().rev().copied().collect();
                1 + hand_walk(n, black_box(&reversed), black_box(Sym(0)), false, false)
            }
            "d_acc_seen" => hand_walk_seen(n, black_box(&syms), black_box(lsym)),
            "d_found_rest" => hand_walk(n, black_box(&syms), black_box(lsym), false, true),
            "d_shelf_pairs" => {
                // The item compared, the shelf handed back: a pair's key.
                hand_walk_pairs(n, black_box(&sym_pairs), black_box(lsym))
            }
            "c_pipe_pair" => hand_pair(n),
            "c_final_by_inarg" => hand_final_by_inarg(n),
            "c_local_limit_hop" => hand_local_limit_hop(n),
            "d_ints_inarg_threshold" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                // The threshold the walk's in_arg: read once a round.
                let t = black_box(len as i64 - 2);
                hand_walk_by(n, black_box(&ints), |x| (x > t).then_some(x), true)
            }
            "d_place_records" => {
                let recs: Vec<(Sym, i64)> = (0..len).map(|i| (Sym(i as u32), i as i64)).collect();
                let f = black_box(len as i64 - 1);
                hand_walk_by(n, black_box(&recs), |(p, fl)| (fl == f).then_some(p), true)
            }
            "d_confirm_found" => hand_walk_confirm(
                n,
                black_box(&syms),
                black_box(lsym),
                black_box(Sym(u32::MAX)),
            ),
            "d_appended_list" => {
                // `append(Places, [Dock], All)` once, in the first arc.
                let mut all: Vec<Sym> = black_box(&syms[..len - 1]).to_vec();
                all.push(black_box(lsym));
                hand_walk(n, black_box(&all), black_box(lsym), true, false)
            }
            _ => unreachable!(),
        };
    }
    match name {
        "c_limit_inarg_echo" => ways!(c_limit_inarg_echo),
        "c_counter_param" => ways!(c_counter_param),
        "c_outarg_cond" => ways!(c_outarg_cond),
        "c_deeper_echo" => ways!(c_deeper_echo),
        "d_target_in_id" => ways!(d_target_in_id),
        "d_id_shares_param" => ways!(d_id_shares_param),
        "d_local_places" => ways!(d_local_places),
        "d_const_ints" => ways!(d_const_ints),
        "d_built_list" => ways!(d_built_list),
        "d_acc_seen" => ways!(d_acc_seen),
        "d_found_rest" => ways!(d_found_rest),
        "d_shelf_pairs" => ways!(d_shelf_pairs),
        "list_search" => ways!(list_search),
        "c_first_param" => ways!(c_first_param),
        "c_float_limit" => ways!(c_float_limit),
        "c_global_count" => ways!(c_global_count),
        "d_walk_first_param" => ways!(d_walk_first_param),
        "d_target_matched_in_id" => ways!(d_target_matched_in_id),
        "d_compare_fn" => ways!(d_compare_fn),
        "c_pipe_pair" => ways!(c_pipe_pair),
        "c_final_by_inarg" => ways!(c_final_by_inarg),
        "c_local_limit_hop" => ways!(c_local_limit_hop),
        "d_ints_inarg_threshold" => ways!(d_ints_inarg_threshold),
        "d_place_records" => ways!(d_place_records),
        "d_confirm_found" => ways!(d_confirm_found),
        "d_appended_list" => ways!(d_appended_list),
        "c_outarg_apply" => ways!(c_outarg_apply),
        "c_global_flag" => ways!(c_global_flag),
        "d_global_visited" => ways!(d_global_visited),
        "d_outarg_when" => ways!(d_outarg_when),
        _ => unreachable!(),
    }
}

/// (c) with the callee computing its out_arg (`c_outarg_apply`: the pipe
/// plus one, which the workload's Prolog user function `succ_of/1`
/// computes: here a Rust addition, so the ratio is not like with like),
/// the caller comparing the pipe with the limit on a neutral situation.
fn hand_succ(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask,
        Test,
        Over,
        Add,
        Added,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut transitions) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                pipe = black_box(0);
                *top = Frame::Ask;
            }
            Frame::Ask => stack.push(Frame::Add),
            Frame::Add => {
                transitions += 1;
                // in_arg X, out_arg X + 1 (after the next situation).
                *top = Frame::Added;
                pipe = black_box(pipe + 1);
            }
            Frame::Added => {
                transitions += 1;
                stack.pop();
                transitions += 1;
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Test;
                }
            }
            Frame::Test => {
                transitions += 1;
                *top = if pipe < black_box(limit) {
                    Frame::Ask
                } else {
                    Frame::Over
                };
            }
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (d) over pairs: the key compared, the shelf handed back.
fn hand_walk_pairs(rounds: i64, pairs: &[(Sym, Sym)], item: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Check(&'a [(Sym, Sym)]),
        On(Sym),
        None,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut transitions) = (0i64, 1u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Check(pairs);
            }
            Frame::Check([]) => {
                transitions += 1;
                *top = Frame::None;
            }
            Frame::Check([(i, s), more @ ..]) => {
                transitions += 1;
                *top = if *i == item {
                    Frame::On(*s)
                } else {
                    Frame::Check(more)
                };
            }
            Frame::On(_) | Frame::None => {
                transitions += 1;
                let shelf = match *top {
                    Frame::On(s) => Some(s),
                    _ => None,
                };
                black_box(shelf);
                stack.pop();
                transitions += 1;
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// (c) `c_pipe_pair`: the pipe a pair (count, limit) set once, the callee
/// counting and handing both back, the caller testing them on a neutral
/// situation.
fn hand_pair(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask,
        Test,
        Over,
        Step,
        Counted,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut transitions) = ((0i64, 0i64), 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                pipe = black_box((0, limit));
                *top = Frame::Ask;
            }
            Frame::Ask => stack.push(Frame::Step),
            Frame::Step => {
                transitions += 1;
                let (n, l) = pipe;
                pipe = black_box((n + 1, l));
                *top = Frame::Counted;
            }
            Frame::Counted => {
                // The callee's final, then the caller's exit arc.
                transitions += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Test;
                }
            }
            Frame::Test => {
                transitions += 1;
                let (n, l) = pipe;
                *top = if n < l { Frame::Ask } else { Frame::Over };
            }
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (c) `c_final_by_inarg`: the count in the pipe and the caller's id, the
/// callee's final chosen by its in_arg (`> 10`).
fn hand_final_by_inarg(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask(i64),
        Over,
        Look,
        Big,
        Small,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut transitions) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                pipe = black_box(0);
                *top = Frame::Ask(0);
            }
            Frame::Ask(_) => stack.push(Frame::Look),
            Frame::Look => {
                transitions += 1;
                *top = if pipe > 10 { Frame::Big } else { Frame::Small };
            }
            Frame::Big | Frame::Small => {
                transitions += 2;
                black_box(matches!(*top, Frame::Big));
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    if let Frame::Ask(i) = *m {
                        let j = i + 1;
                        pipe = black_box(j);
                        *m = if j < limit {
                            Frame::Ask(j)
                        } else {
                            Frame::Over
                        };
                    }
                }
            }
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (c) `c_local_limit_hop`: the limit a local, the count in the pipe,
/// incremented two levels down, passed through `hop`'s neutral situation.
fn hand_local_limit_hop(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask,
        Test,
        Over,
        Pass,
        Down,
        Done,
        Add,
        Bumped,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut local, mut transitions) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                local = black_box(limit);
                pipe = black_box(0);
                *top = Frame::Ask;
            }
            Frame::Ask => stack.push(Frame::Pass),
            Frame::Pass => {
                transitions += 1;
                pipe = black_box(pipe);
                *top = Frame::Down;
            }
            Frame::Down => stack.push(Frame::Add),
            Frame::Add => {
                transitions += 1;
                pipe = black_box(pipe + 1);
                *top = Frame::Bumped;
            }
            Frame::Bumped => {
                transitions += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Done;
                }
            }
            Frame::Done => {
                transitions += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Test;
                }
            }
            Frame::Test => {
                transitions += 1;
                *top = if pipe < black_box(local) {
                    Frame::Ask
                } else {
                    Frame::Over
                };
            }
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (d) with the test a closure: `hit` gives what the final hands back when
/// an element is the one looked for (a threshold, a record's field).
fn hand_walk_by<T: Copy, R: Copy>(
    rounds: i64,
    items: &[T],
    hit: impl Fn(T) -> Option<R>,
    start: bool,
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a, T, R> {
        Round,
        Stop,
        Begin,
        Try(&'a [T]),
        Final(Option<R>),
    }
    let mut stack: Vec<Frame<T, R>> = vec![Frame::Round];
    let (mut n, mut transitions) = (0i64, u64::from(start));
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items);
            }
            Frame::Try([]) => {
                transitions += 1;
                *top = Frame::Final(None);
            }
            Frame::Try([p, ps @ ..]) => {
                transitions += 1;
                *top = match hit(*p) {
                    Some(r) => Frame::Final(Some(r)),
                    None => Frame::Try(ps),
                };
            }
            Frame::Final(exit) => {
                transitions += 2;
                black_box(exit);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// (d) `d_confirm_found`: the element found is confirmed by a nested
/// call (`sure(P)`, one neutral step) before the walk ends.
fn hand_walk_confirm(rounds: i64, items: &[Sym], target: Sym, unknown: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Try(&'a [Sym]),
        Confirm(Sym, &'a [Sym]),
        Ask(Sym),
        Yes,
        No,
        Found(Sym),
        NotFound,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut transitions) = (0i64, 1u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items);
            }
            Frame::Try([]) => {
                transitions += 1;
                *top = Frame::NotFound;
            }
            Frame::Try([p, ps @ ..]) => {
                transitions += 1;
                *top = if *p == target {
                    Frame::Confirm(*p, ps)
                } else {
                    Frame::Try(ps)
                };
            }
            Frame::Confirm(p, _) => stack.push(Frame::Ask(p)),
            Frame::Ask(p) => {
                transitions += 1;
                *top = if p == unknown { Frame::No } else { Frame::Yes };
            }
            Frame::Yes | Frame::No => {
                // `sure`'s final, then `confirm`'s exit arc.
                transitions += 2;
                let yes = matches!(*top, Frame::Yes);
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    if let Frame::Confirm(p, ps) = *m {
                        *m = if yes { Frame::Found(p) } else { Frame::Try(ps) };
                    }
                }
            }
            Frame::Found(_) | Frame::NotFound => {
                transitions += 2;
                let found = match *top {
                    Frame::Found(p) => Some(p),
                    _ => None,
                };
                black_box(found);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// (c) with a flag: the callee counts in a global (`jobs`) and sets a
/// global flag (`done`) when the count reaches the limit (one more
/// transition, `finish`); the caller tests the flag after each call.
/// The globals are plain Rust variables (`black_box`ed where written).
fn hand_flag(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Ask,
        Over,
        Work,
        Finish,
        Back,
    }
    let mut stack: Vec<Frame> = vec![Frame::Ask];
    let (mut jobs, mut done, mut transitions) = (0i64, false, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Ask => stack.push(Frame::Work),
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
            Frame::Work => {
                transitions += 1;
                jobs = black_box(jobs + 1);
                *top = if jobs >= limit {
                    Frame::Finish
                } else {
                    Frame::Back
                };
            }
            Frame::Finish => {
                transitions += 1;
                done = black_box(true);
                *top = Frame::Back;
            }
            Frame::Back => {
                transitions += 1;
                stack.pop();
                transitions += 1;
                if let Some(m) = stack.last_mut() {
                    *m = if black_box(done) {
                        Frame::Over
                    } else {
                        Frame::Ask
                    };
                }
            }
        }
    }
    transitions
}

/// (d) counting the places visited in a global (a plain `i64` here,
/// `black_box`ed where written), the caller reading it after each round
/// against its budget.
fn hand_walk_visited(budget: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Try(&'a [Sym]),
        Final(Option<Sym>),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut visited, mut transitions) = (0i64, 1u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items);
            }
            Frame::Try([]) => {
                transitions += 1;
                *top = Frame::Final(None);
            }
            Frame::Try([p, ps @ ..]) => {
                transitions += 1;
                visited = black_box(visited + 1);
                *top = if *p == target {
                    Frame::Final(Some(*p))
                } else {
                    Frame::Try(ps)
                };
            }
            Frame::Final(found) => {
                transitions += 1;
                black_box(found);
                stack.pop();
                transitions += 1;
                if let Some(m) = stack.last_mut() {
                    *m = if black_box(visited) < budget {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    transitions
}

/// (d) `d_outarg_when`: [`hand_walk`] whose walking step also sets the
/// pipe to whether the place looked at is the target (`here` or
/// `elsewhere`, the out_arg `apply(when(_, _, _), [P == Target, ..])`; a
/// `bool` here, `black_box`ed where written).
fn hand_walk_flag(rounds: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Try(&'a [Sym]),
        Final(Option<Sym>),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut transitions, mut here) = (0i64, 1u64, false);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items);
            }
            Frame::Try([]) => {
                transitions += 1;
                *top = Frame::Final(None);
            }
            Frame::Try([p, ps @ ..]) => {
                transitions += 1;
                let found = *p == target;
                here = black_box(found);
                *top = if found {
                    Frame::Final(Some(*p))
                } else {
                    Frame::Try(ps)
                };
            }
            Frame::Final(found) => {
                transitions += 1;
                black_box(found);
                stack.pop();
                transitions += 1;
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n < rounds {
                        Frame::Round
                    } else {
                        Frame::Stop
                    };
                }
            }
        }
    }
    black_box(here);
    transitions
}

const ALL: [&str; 29] = [
    "c_limit_inarg_echo",
    "c_counter_param",
    "c_outarg_cond",
    "c_deeper_echo",
    "d_target_in_id",
    "d_id_shares_param",
    "d_local_places",
    "d_const_ints",
    "d_built_list",
    "d_acc_seen",
    "d_found_rest",
    "d_shelf_pairs",
    "c_first_param",
    "c_float_limit",
    "d_walk_first_param",
    "d_target_matched_in_id",
    "c_global_count",
    "d_compare_fn",
    "c_pipe_pair",
    "c_final_by_inarg",
    "c_local_limit_hop",
    "d_ints_inarg_threshold",
    "d_place_records",
    "d_confirm_found",
    "d_appended_list",
    "c_outarg_apply",
    "c_global_flag",
    "d_global_visited",
    "d_outarg_when",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("check") {
        for name in ALL {
            for len in [8, 13] {
                let t: Vec<u64> = ["compiled", "interp", "hand"]
                    .iter()
                    .map(|w| one(name, w, 7, len))
                    .collect();
                println!("{name} {len}: {t:?}");
                assert!(t[0] == t[1] && t[1] == t[2], "{name}: {t:?}");
            }
        }
        return;
    }
    let [name, way, n, rest @ ..] = &args[..] else {
        panic!("usage: shapes_prof WORKLOAD compiled|interp|hand ROUNDS [PLACES]");
    };
    let len = rest.first().map_or(8, |l| l.parse().expect("places"));
    let t = one(name, way, n.parse().expect("rounds"), len);
    println!("{t}");
}
