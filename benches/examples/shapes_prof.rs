//! Workloads of shapes (c) and (d) of issue 37 written from the issue's
//! text (`tests/typed/shapes/c_*`, `d_*` of helper `ngen11`), each run three
//! ways for counting instructions with callgrind: the compiled task
//! (`include_dm!`, native code where the compiler gives it), the
//! interpreter (`sitlogc run`'s plans) and a hand-written Rust machine doing
//! the same work (atoms as an interned index, lists as slices, frames on an
//! explicit stack, `black_box` where `benches/benches/compiled.rs` puts it;
//! the machines are `benches/src/hand.rs`'s, which the bench includes too).
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

#[path = "../src/hand.rs"]
mod hand;
use hand::*;
#[path = "../src/hand22.rs"]
mod hand22;
use hand22::*;
#[path = "../src/hand24.rs"]
mod hand24;
use hand24::*;
#[path = "../src/hand25.rs"]
mod hand25;
use hand25::*;
#[path = "../src/hand25w.rs"]
mod hand25w;
use hand25w::*;
#[path = "../src/hand25f.rs"]
mod hand25f;
use hand25f::*;
#[path = "../src/hand_nre24.rs"]
mod hand_nre24;
use hand_nre24::*;
#[path = "../src/hand25g.rs"]
mod hand25g;
use hand25g::*;
#[path = "../src/hand_nmemo25.rs"]
mod hand_nmemo25;
use hand_nmemo25::*;

// Helper `nglob24`'s (issue 37): a global list grown a step, read each step.
mod g24_d_grow_list {
    sitlog_macros::include_dm!("../tests/typed/nglob24/g24_d_grow_list");
}
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
mod c_local_count {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_local_count");
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
// Helper `nsurvey16`'s (session 15).
mod d_room_compounds {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_room_compounds");
}
mod d_pair_key_rest {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_pair_key_rest");
}
mod d_visits_in_id {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_visits_in_id");
}
mod d_first_of_goals {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_first_of_goals");
}
mod d_goto_exit_arc {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_goto_exit_arc");
}
mod d_found_into_next {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_found_into_next");
}
mod c_count_two_levels {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_count_two_levels");
}
// Helper `nwhen16`'s (session 15): `when/3` with an arithmetic condition.
mod d_when_arith {
    sitlog_macros::include_dm!("../tests/typed/shapes/d_when_arith");
}
// Helper `nrec16`'s (session 15): a recursive situation's in_arg pattern.
mod c_rec_inarg_pair {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_rec_inarg_pair");
}
// Helper `review17`'s (session 16): written without reading `tests/typed/shapes`.
mod r17_c_charge_when {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_c_charge_when");
}
mod r17_c_courier_global {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_c_courier_global");
}
mod r17_c_odometer {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_c_odometer");
}
mod r17_c_job_pair {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_c_job_pair");
}
mod r17_d_dock_when {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_d_dock_when");
}
mod r17_d_two_lists {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_d_two_lists");
}
mod r17_d_prog_rooms {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_d_prog_rooms");
}
mod r17_d_readings_deep {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_d_readings_deep");
}
mod r17_d_announce {
    sitlog_macros::include_dm!("../tests/typed/review17/r17_d_announce");
}
// Helper `nwait17`'s (session 16): a variable in_arg only the call reads.
mod c_call_reads_inarg {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_call_reads_inarg");
}
mod c_expr_compare {
    sitlog_macros::include_dm!("../tests/typed/shapes/c_expr_compare");
}
// Helper `review18`'s (session 17): written without reading `tests/typed/shapes`
// or `tests/typed/review17`.
mod r18_c_deep_limit {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_c_deep_limit");
}
mod r18_c_clerk_global {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_c_clerk_global");
}
mod r18_d_item_qty {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_item_qty");
}
mod r18_d_room_of {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_room_of");
}
mod r18_d_fn_next {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_fn_next");
}
// Two lists walked in step (`hand_r18_lockstep` the machine of both; their
// generated Rust did not compile on main `0c8eab3`, E0505: fixed by `nlock18`).
mod r18_d_lockstep {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_lockstep");
}
mod r18_d_lockstep_any {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_lockstep_any");
}
mod r18_d_callee_list {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_callee_list");
}
mod r18_d_yes_no {
    sitlog_macros::include_dm!("../tests/typed/review18/r18_d_yes_no");
}
// Helper `review19`'s (session 18): written without reading `tests/typed/shapes`,
// `tests/typed/review17` or `tests/typed/review18`.
mod r19_d_shelves {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_shelves");
}
mod r19_d_collect_out {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_collect_out");
}
mod r19_c_done_pair {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_c_done_pair");
}
mod r19_d_global_goal {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_global_goal");
}
mod r19_c_ping_pong {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_c_ping_pong");
}
mod r19_d_chain3 {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_chain3");
}
mod r19_d_when_qty {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_when_qty");
}
mod r19_d_prolog_first {
    sitlog_macros::include_dm!("../tests/typed/review19/r19_d_prolog_first");
}
mod r22_c_stage_global {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_c_stage_global");
}
mod r22_c_ferry_two {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_c_ferry_two");
}
mod r22_c_lap_pipe {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_c_lap_pipe");
}
mod r22_c_rung_id {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_c_rung_id");
}
mod r22_d_sweep_say {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_d_sweep_say");
}
mod r22_d_stock_expect {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_d_stock_expect");
}
mod r22_d_floor_fn {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_d_floor_fn");
}
mod r22_d_goal_local {
    sitlog_macros::include_dm!("../tests/typed/review22/r22_d_goal_local");
}
// Helper `review24`'s (session 23).
mod r24_c_winch_param {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_c_winch_param");
}
mod n25_c_tally_grade {
    sitlog_macros::include_dm!("../tests/typed/nwinch25/n25_c_tally_grade");
}
mod r24_c_mill_nested {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_c_mill_nested");
}
mod r24_d_gauge_guard {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_d_gauge_guard");
}
mod r24_d_where_pairs {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_d_where_pairs");
}
mod r24_d_sift_two_lists {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_d_sift_two_lists");
}
mod r24_d_near_floats {
    sitlog_macros::include_dm!("../tests/typed/review24/r24_d_near_floats");
}
// Helper `review25`'s (session 24).
mod r25_c_pass_limit {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_c_pass_limit");
}
mod r25_c_rota_list {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_c_rota_list");
}
mod r25_d_obj_records {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_d_obj_records");
}
mod r25_d_prolog_route {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_d_prolog_route");
}
mod r25_d_filter_out {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_d_filter_out");
}
mod r25_d_strings {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_d_strings");
}
mod r25_d_mutual_walk {
    sitlog_macros::include_dm!("../tests/typed/review25/r25_d_mutual_walk");
}
// Helper nfloat25's (d): floats in a band, a plain function's answer the next situation.
mod n25_d_float_band {
    sitlog_macros::include_dm!("../tests/typed/nfloat25/n25_d_float_band");
}
// Helper nre24's (d): a frame entered again from the machine at each place.
mod n24_d_note_walk {
    sitlog_macros::include_dm!("../tests/typed/nre24/n24_d_note_walk");
}
// Helper ngauge25's: a float `is` in a prog (c), in a next situation's
// argument (d).
mod g25_c_float_prog {
    sitlog_macros::include_dm!("../tests/typed/ngauge25/g25_c_float_prog");
}
mod g25_d_float_next {
    sitlog_macros::include_dm!("../tests/typed/ngauge25/g25_d_float_next");
}
// Helper nmemo25's (d): the same walk with an accumulator `[S|Seen]`.
mod n25_d_tally_walk {
    sitlog_macros::include_dm!("../tests/typed/nmemo25/n25_d_tally_walk");
}
// Ours (`benches/dms`), for comparing the compiled and interpreted runs
// of a change with the benchmarks'; their hand-written way is the one
// `benches/benches/compiled.rs` times (`hand_echo_calls`,
// `hand_list_search`, shared through `benches/src/hand.rs`).
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
/// (`d_compare_fn`'s `same_place/2`), both ways alike; with
/// `SHAPES_ENGINE_ONLY` set, every call a query of the engine (its plain
/// functions not run natively: the figures before helper `nufn17`).
fn run_prolog<A: app::App>(app: &A, main: &str, name: &str) -> u64 {
    let mut f = Functions::standard();
    let prolog =
        sitlog_compiler::run::install_prolog(&interpreter(name), &mut f, Default::default())
            .expect("the workload's Prolog loads");
    if let (Some(p), true) = (prolog, std::env::var_os("SHAPES_ENGINE_ONLY").is_some()) {
        p.install_with(&mut f, false);
    }
    run_fns(app, main, None, f)
}

thread_local! {
    /// The script of test mode for the next run (`r18_d_yes_no`'s answers;
    /// empty for the others).
    static SCRIPT: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

fn run_fns<A: app::App>(app: &A, main: &str, in_arg: Option<&str>, functions: Functions) -> u64 {
    let script = SCRIPT.with(|s| s.borrow().clone());
    let mut perception = ScriptPerception::new("script", script);
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

/// A workload whose main DM `main` starts with the pipe `n` (helper
/// `review22`'s (c)), compiled (`app`) or interpreted.
fn piped<A: app::App>(way: &str, app: &A, name: &str, main: &str, n: i64) -> u64 {
    let n = n.to_string();
    match way {
        "compiled" => run_piped(app, main, Some(&n)),
        _ => run_piped(&Resolved::new(&interpreter(name)), main, Some(&n)),
    }
}

/// [`piped`] of a main DM call with arguments, the pipe starting at 0.
fn piped_main<A: app::App>(way: &str, app: &A, name: &str, main: &str) -> u64 {
    match way {
        "compiled" => run_piped(app, main, Some("0")),
        _ => run_piped(&Resolved::new(&interpreter(name)), main, Some("0")),
    }
}

fn interpreter(dir: &str) -> Ir {
    let root = match dir {
        "echo_calls" | "list_search" => "dms",
        _ if dir.starts_with("r17_") => "../tests/typed/review17",
        _ if dir.starts_with("r18_") => "../tests/typed/review18",
        _ if dir.starts_with("r19_") => "../tests/typed/review19",
        _ if dir.starts_with("r22_") => "../tests/typed/review22",
        _ if dir.starts_with("r24_") => "../tests/typed/review24",
        _ if dir.starts_with("r25_") => "../tests/typed/review25",
        _ if dir.starts_with("n24_") => "../tests/typed/nre24",
        _ if dir.starts_with("g25_") => "../tests/typed/ngauge25",
        _ if dir.starts_with("n25_c_tally") => "../tests/typed/nwinch25",
        _ if dir.starts_with("n25_") => "../tests/typed/nfloat25",
        _ if dir.starts_with("n25_") => "../tests/typed/nmemo25",
        _ if dir.starts_with("g24_") => "../tests/typed/nglob24",
        _ => "../tests/typed/shapes",
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(root).join(dir);
    let (checked, _) = sitlog_compiler::check_path(&dir).expect("readable");
    sitlog_compiler::ir::lower(&checked.expect("checks"))
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
    SCRIPT.with(|s| s.borrow_mut().clear());
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
        "d_when_arith" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("hunt({n}, [{}], {})", ints.join(","), len / 2)
        }
        "d_const_ints" => format!("drill({n}, 64)"),
        "d_built_list" => format!("patrol({n}, {list}, p0)"),
        "d_acc_seen" => format!("survey({n}, {list}, {last})"),
        "d_found_rest" => format!("visit({n}, {list}, {last})"),
        "d_shelf_pairs" => format!("stock({n}, {pairs_text}, {last})"),
        "list_search" => format!("main({n}, {list}, {last})"),
        "c_pipe_pair" | "c_final_by_inarg" | "c_local_limit_hop" | "c_local_count"
        | "c_rec_inarg_pair" | "c_call_reads_inarg" | "c_expr_compare" => {
            format!("relay({n})")
        }
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
        "d_room_compounds" => {
            let rooms: Vec<String> = (0..len).map(|i| format!("room(p{i})")).collect();
            format!("hunt({n}, [{}], {last})", rooms.join(","))
        }
        "d_pair_key_rest" => {
            let pairs: Vec<String> = (0..len).map(|i| format!("p{i}-{i}")).collect();
            format!("tour({n}, [{}], {last})", pairs.join(","))
        }
        "d_visits_in_id" => format!("survey({n}, {list}, {last})"),
        "d_first_of_goals" => format!("hunt({n}, {list}, [nowhere, {last}])"),
        "d_goto_exit_arc" | "d_found_into_next" => format!("hunt({n}, {list}, {last})"),
        "c_count_two_levels" => format!("relay({n})"),
        "r17_c_charge_when" => format!("charger({n})"),
        "r17_c_courier_global" => format!("mission({n})"),
        "r17_c_odometer" => format!("patrol({n})"),
        "r17_c_job_pair" => format!("shift({n})"),
        "r17_d_dock_when" => format!("fleet({last}, {n}, {list})"),
        "r17_d_two_lists" => format!("audit({n}, {list}, {last})"),
        "r17_d_prog_rooms" => format!("tour({n}, cellar)"),
        "r17_d_announce" => format!("rounds({n}, {list}, {last})"),
        "r17_d_readings_deep" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("monitor({n}, [{}], {})", ints.join(","), len - 2)
        }
        "r18_c_deep_limit" => format!("top({n})"),
        "r18_c_clerk_global" => format!("boss({n})"),
        "r18_d_item_qty" => {
            let items: Vec<String> = (0..len)
                .map(|i| format!("item(p{i},{})", i % 7 + 1))
                .collect();
            format!("stock({n}, [{}], {last})", items.join(","))
        }
        "r18_d_room_of" => {
            let pairs: Vec<String> = (0..len).map(|i| format!("s{}-p{i}", i % 5)).collect();
            format!(
                "tidy({n}, [{}], {last}, s{})",
                pairs.join(","),
                (len - 1) % 5
            )
        }
        "r18_d_fn_next" => format!("errand({n}, {list}, {last})"),
        "r18_d_callee_list" => format!("courier({n}, {list}, p0)"),
        "r18_d_lockstep" | "r18_d_lockstep_any" => {
            let (xs, ys) = lockstep_lists(len);
            let show = |v: Vec<i64>| v.iter().map(i64::to_string).collect::<Vec<_>>().join(",");
            format!("gauge({n}, [{}], [{}], 0)", show(xs), show(ys))
        }
        "r18_d_yes_no" => {
            let mut round = "no.\n".repeat(len - 1);
            round.push_str("yes.\n");
            SCRIPT.with(|s| *s.borrow_mut() = round.repeat(n as usize));
            format!("ask({n}, {list})")
        }
        "r19_d_shelves" => format!("pick({n}, {}, {last})", shelves_text(len)),
        "r19_d_collect_out" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("harvest({n}, [{}], {})", ints.join(","), len / 2)
        }
        "r19_c_done_pair" if way != "hand" => {
            let n = n.to_string();
            return match way {
                "compiled" => run_piped(r19_c_done_pair::program(), "relay", Some(&n)),
                _ => run_piped(&Resolved::new(&interpreter(name)), "relay", Some(&n)),
            };
        }
        "r19_c_done_pair" => String::new(),
        "r19_d_global_goal" => format!("seek({n}, {list}, {last})"),
        "r19_c_ping_pong" => format!("rally({n}, 2)"),
        "r19_d_chain3" => format!("audit({n}, {list}, {last})"),
        "r19_d_when_qty" => {
            let items: Vec<String> = (0..len)
                .map(|i| format!("item(p{i},{})", if i + 1 == len { 9 } else { i % 5 }))
                .collect();
            format!("order({n}, [{}], 5)", items.join(","))
        }
        "r19_d_prolog_first" => format!(
            "weigh({n}, [{}])",
            crates(len)
                .iter()
                .map(i64::to_string)
                .collect::<Vec<_>>()
                .join(",")
        ),
        // Helper review22's (c): the limit the pipe the main DM starts with.
        "r22_c_stage_global" if way != "hand" => {
            return piped(way, r22_c_stage_global::program(), name, "launch", n)
        }
        "r22_c_ferry_two" if way != "hand" => {
            return piped(way, r22_c_ferry_two::program(), name, "shuttle", n)
        }
        "r22_c_lap_pipe" if way != "hand" => {
            return piped(way, r22_c_lap_pipe::program(), name, "track", n)
        }
        "r22_c_rung_id" if way != "hand" => {
            return piped(way, r22_c_rung_id::program(), name, "ladder", n)
        }
        "r22_c_stage_global" | "r22_c_ferry_two" | "r22_c_lap_pipe" | "r22_c_rung_id" => {
            String::new()
        }
        "r22_d_sweep_say" => format!("patrol({n}, {list}, {last})"),
        // Helper `nglob24`'s: `n` steps, the list `n` long at the end (its
        // places unused).
        "g24_d_grow_list" => format!("gather({n})"),
        "r22_d_stock_expect" => {
            let pairs: Vec<String> = (0..len).map(|i| format!("p{i}-{}", i % 7 + 1)).collect();
            format!("inventory({n}, [{}], {last})", pairs.join(","))
        }
        "r22_d_floor_fn" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("meter({n}, [{}], {})", ints.join(","), len - 1)
        }
        "r22_d_goal_local" => format!("errands({n}, {list}, {last})"),
        // Helper review24's: (c) the limit the pipe the main DM starts with.
        "r24_c_winch_param" if way != "hand" => {
            return piped(way, r24_c_winch_param::program(), name, "winch", n)
        }
        "r24_c_mill_nested" if way != "hand" => {
            return piped(way, r24_c_mill_nested::program(), name, "works", n)
        }
        "r24_c_winch_param" | "r24_c_mill_nested" => String::new(),
        // Helper nwinch25's: (c) the limit the pipe the main DM starts with.
        "n25_c_tally_grade" if way != "hand" => {
            return piped(way, n25_c_tally_grade::program(), name, "tally", n)
        }
        "n25_c_tally_grade" => String::new(),
        "r24_d_gauge_guard" => {
            let ints: Vec<String> = (0..len).map(|i| i.to_string()).collect();
            format!("gauge({n}, [{}], {})", ints.join(","), len - 2)
        }
        "r24_d_where_pairs" => format!("where({n}, {pairs_text}, {last})"),
        "r24_d_sift_two_lists" => format!("sort_room({n}, {list}, {last})"),
        "r24_d_near_floats" => {
            let freqs: Vec<String> = (0..len).map(|i| format!("{i}.5")).collect();
            format!("tune({n}, [{}], {}.5)", freqs.join(","), len - 1)
        }
        // Helper review25's: (c) the count the pipe (from 0), the limit an
        // argument of the main DM.
        "r25_c_pass_limit" if way != "hand" => {
            return piped_main(way, r25_c_pass_limit::program(), name, &format!("lap({n})"))
        }
        "r25_c_rota_list" if way != "hand" => {
            let main = format!("rota({n}, [ann, bob, cy])");
            return piped_main(way, r25_c_rota_list::program(), name, &main);
        }
        "r25_c_pass_limit" | "r25_c_rota_list" => String::new(),
        "r25_d_obj_records" => {
            let objs: Vec<String> = r25_objs(len)
                .iter()
                .enumerate()
                .map(|(i, (k, w))| format!("obj(p{i},{},{w})", if *k { "kitchen" } else { "hall" }))
                .collect();
            format!("haul({n}, [{}], 50)", objs.join(","))
        }
        "r25_d_prolog_route" => {
            let stops: Vec<String> = (0..len)
                .map(|i| {
                    if r25_is_hall(i, len) {
                        "hall".to_owned()
                    } else {
                        format!("p{i}")
                    }
                })
                .collect();
            format!("errand({n}, [{}], {last})", stops.join(","))
        }
        "r25_d_filter_out" => {
            let stops: Vec<String> = (0..len)
                .map(|i| {
                    if r25_is_hall(i, len) {
                        "hall".to_owned()
                    } else {
                        format!("p{i}")
                    }
                })
                .collect();
            format!("sweep({n}, [{}], hall)", stops.join(","))
        }
        "r25_d_strings" => {
            let goods: Vec<String> = (0..len).map(|i| format!("\"p{i}\"")).collect();
            format!("shop({n}, [{}], \"{last}\")", goods.join(","))
        }
        "r25_d_mutual_walk" => format!("stroll({n}, {list}, {last})"),
        // Helper ngauge25's: the charge a float; weights `i % 3 + 1`, a
        // cap never passed (every place walked).
        "g25_c_float_prog" => format!("battery({n}, 0.0)"),
        "g25_d_float_next" => {
            let ws: Vec<String> = (0..len).map(|i| (i % 3 + 1).to_string()).collect();
            format!("tally({n}, [{}], 1.0e9)", ws.join(","))
        }
        "n25_d_float_band" => {
            let xs: Vec<String> = (0..len).map(|i| format!("{i}.5")).collect();
            format!("band({n}, [{}], {}.25)", xs.join(","), len - 1)
        }
        "n24_d_note_walk" | "n25_d_tally_walk" => format!("survey({n}, {list}, {last})"),
        "echo_calls" if way == "hand" => return hand_echo_calls(black_box(n)),
        "echo_calls" => {
            let n = n.to_string();
            return match way {
                "compiled" => run_piped(echo_calls::program(), "main", Some(&n)),
                "interp" => run_piped(&Resolved::new(&interpreter(name)), "main", Some(&n)),
                _ => unreachable!(),
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
            "d_when_arith" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                hand_walk_when_arith(n, black_box(&ints), black_box(len as i64 / 2))
            }
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
            "list_search" => hand_list_search(n, black_box(&syms), black_box(lsym)),
            "c_pipe_pair" => hand_pair(n),
            "c_rec_inarg_pair" => hand_rec_pair(n),
            "c_call_reads_inarg" => hand_call_reads_inarg(n),
            "c_expr_compare" => hand_expr_compare(n),
            "c_final_by_inarg" => hand_final_by_inarg(n),
            "c_local_count" => hand_local_count(n),
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
            "d_room_compounds" => {
                let rooms: Vec<Room> = syms.iter().map(|&s| Room(s)).collect();
                let t = black_box(lsym);
                hand_walk_by(
                    n,
                    black_box(&rooms),
                    |Room(r)| (r == t).then_some(Room(r)),
                    true,
                )
            }
            "d_pair_key_rest" => {
                let pairs: Vec<(Sym, i64)> = (0..len).map(|i| (Sym(i as u32), i as i64)).collect();
                let t = black_box(lsym);
                hand_walk_by(n, black_box(&pairs), |(p, _)| (p == t).then_some(p), false)
            }
            "d_visits_in_id" => hand_walk_count(n, black_box(&syms), black_box(lsym)),
            "d_first_of_goals" => {
                // `member(P, Goals)`: a scan of a slice of two.
                let goals = [Sym(u32::MAX), lsym];
                let goals = black_box(&goals[..]);
                hand_walk_by(
                    n,
                    black_box(&syms),
                    |p| goals.contains(&p).then_some(p),
                    true,
                )
            }
            "d_goto_exit_arc" => hand_walk_goto(n, black_box(&syms), black_box(lsym)),
            "d_found_into_next" => hand_walk_seen_next(n, black_box(&syms), black_box(lsym)),
            "c_count_two_levels" => hand_two_levels(n),
            "r18_c_deep_limit" => hand_r18_deep_limit(n),
            "r18_c_clerk_global" => hand_r18_clerk(n),
            "r18_d_item_qty" => {
                let items: Vec<Item> = (0..len)
                    .map(|i| Item(Sym(i as u32), i as i64 % 7 + 1))
                    .collect();
                hand_r18_item_qty(n, black_box(&items), black_box(lsym))
            }
            "r18_d_room_of" => {
                let pairs: Vec<(Sym, Sym)> = (0..len as u32)
                    .map(|i| (Sym(1000 + i % 5), Sym(i)))
                    .collect();
                let home = Sym(1000 + (len as u32 - 1) % 5);
                hand_r18_room_of(n, black_box(&pairs), black_box(lsym), black_box(home))
            }
            "r18_d_fn_next" => {
                let t = black_box(lsym);
                hand_walk_by(n, black_box(&syms), |p| (p == t).then_some(p), false)
            }
            "r18_d_callee_list" => hand_r18_callee_list(n, black_box(&syms), black_box(Sym(0))),
            "r18_d_lockstep" | "r18_d_lockstep_any" => {
                let (xs, ys) = lockstep_lists(len);
                hand_r18_lockstep(n, black_box(&xs), black_box(&ys), black_box(0))
            }
            "r18_d_yes_no" => {
                let mut round = "no.\n".repeat(len - 1);
                round.push_str("yes.\n");
                let script = round.repeat(n as usize);
                hand_r18_yes_no(n, black_box(&syms), black_box(&script))
            }
            "r19_d_shelves" => {
                let shelves: Vec<Vec<Sym>> = syms.chunks(4).map(<[Sym]>::to_vec).collect();
                hand_r19_shelves(n, black_box(&shelves), black_box(lsym))
            }
            "r19_d_collect_out" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                hand_r19_collect_out(n, black_box(&ints), black_box(len as i64 / 2))
            }
            "r19_c_done_pair" => hand_r19_done_pair(n),
            "r19_d_global_goal" => hand_r19_global_goal(n, black_box(&syms), black_box(lsym)),
            "r19_c_ping_pong" => hand_r19_ping_pong(n, black_box(2)),
            "r19_d_chain3" => hand_r19_chain3(n, black_box(&syms), black_box(lsym)),
            "r19_d_when_qty" => {
                let items: Vec<Item> = (0..len)
                    .map(|i| Item(Sym(i as u32), if i + 1 == len { 9 } else { i as i64 % 5 }))
                    .collect();
                hand_r19_when_qty(n, black_box(&items), black_box(5))
            }
            "r19_d_prolog_first" => {
                hand_r19_prolog_first(n, black_box(&crates(len)), black_box(|w| w >= 1000))
            }
            "r22_c_stage_global" => hand_r22_stage_global(n),
            "g24_d_grow_list" => hand_g24_grow_list(n),
            "r22_c_ferry_two" => hand_r22_ferry_two(n),
            "r22_c_lap_pipe" => hand_r22_lap_pipe(n),
            "r22_c_rung_id" => hand_r22_rung_id(n),
            "r22_d_sweep_say" => {
                let names: Vec<String> = (0..len).map(|i| format!("p{i}")).collect();
                hand_r22_sweep_say(n, black_box(&syms), black_box(&names), black_box(lsym))
            }
            "r22_d_stock_expect" => {
                let stock: Vec<(Sym, i64)> = (0..len)
                    .map(|i| (Sym(i as u32), i as i64 % 7 + 1))
                    .collect();
                hand_r22_stock_expect(n, black_box(&stock), black_box(lsym))
            }
            "r22_d_floor_fn" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                hand_r22_floor_fn(
                    n,
                    black_box(&ints),
                    black_box(len as i64 - 1),
                    black_box(|x, f| x >= f),
                )
            }
            "r22_d_goal_local" => hand_r22_goal_local(n, black_box(&syms), black_box(lsym)),
            "r24_c_winch_param" => hand_r24_winch_param(n),
            "n25_c_tally_grade" => hand_n25_tally_grade(n),
            "r24_c_mill_nested" => hand_r24_mill_nested(n),
            "r24_d_gauge_guard" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                hand_r24_gauge_guard(n, black_box(&ints), black_box(len as i64 - 2))
            }
            "r24_d_where_pairs" => {
                let names: Vec<String> = (0..len).map(|i| format!("p{i}")).collect();
                let places: Vec<String> = (0..5).map(|i| format!("s{i}")).collect();
                hand_r24_where_pairs(
                    n,
                    black_box(&sym_pairs),
                    black_box(lsym),
                    black_box(&names),
                    black_box(&places),
                )
            }
            "r24_d_sift_two_lists" => hand_r24_sift_two_lists(n, black_box(&syms), black_box(lsym)),
            "r24_d_near_floats" => {
                let freqs: Vec<f64> = (0..len).map(|i| i as f64 + 0.5).collect();
                hand_r24_near_floats(
                    n,
                    black_box(&freqs),
                    black_box((len - 1) as f64 + 0.5),
                    black_box(|x: f64, t: f64| (x - t).abs() < 0.1),
                )
            }
            "n25_d_float_band" => {
                let xs: Vec<f64> = (0..len).map(|i| i as f64 + 0.5).collect();
                hand_n25_float_band(
                    n,
                    black_box(&xs),
                    black_box((len - 1) as f64 + 0.25),
                    black_box(|x: f64, lo: f64| {
                        let m = (x - lo) / 2.0;
                        (0.0..=0.25).contains(&m)
                    }),
                )
            }
            "n25_d_tally_walk" => hand_n25_tally_walk(
                n,
                black_box(&syms),
                black_box(lsym),
                black_box(|s| {
                    black_box(s);
                }),
            ),
            "n24_d_note_walk" => hand_n24_note_walk(
                n,
                black_box(&syms),
                black_box(lsym),
                black_box(|s| {
                    black_box(s);
                }),
            ),
            "r25_c_pass_limit" => hand_r25_pass_limit(n),
            "r25_c_rota_list" => {
                let crew = [Sym(10_000), Sym(10_001), Sym(10_002)];
                hand_r25_rota_list(n, black_box(&crew), black_box(Sym(10_002)))
            }
            "r25_d_obj_records" => {
                let (kitchen, hall) = (Sym(10_001), Sym(10_000));
                let objs: Vec<Obj> = r25_objs(len)
                    .iter()
                    .enumerate()
                    .map(|(i, (k, w))| Obj(Sym(i as u32), if *k { kitchen } else { hall }, *w))
                    .collect();
                hand_r25_obj_records(n, black_box(&objs), black_box(50), black_box(kitchen))
            }
            "r25_d_prolog_route" | "r25_d_filter_out" => {
                let (hall, kitchen) = (Sym(10_000), Sym(10_001));
                let stops: Vec<Sym> = (0..len)
                    .map(|i| {
                        if r25_is_hall(i, len) {
                            hall
                        } else {
                            Sym(i as u32)
                        }
                    })
                    .collect();
                if name == "r25_d_filter_out" {
                    hand_r25_filter_out(n, black_box(&stops), black_box(hall))
                } else {
                    hand_r25_prolog_route(
                        n,
                        black_box(&stops),
                        black_box(lsym),
                        black_box(hall),
                        black_box(kitchen),
                    )
                }
            }
            "r25_d_strings" => {
                let goods: Vec<Vec<u8>> = (0..len).map(|i| format!("p{i}").into_bytes()).collect();
                let want = format!("p{}", len - 1).into_bytes();
                hand_r25_strings(n, black_box(&goods), black_box(&want))
            }
            "r25_d_mutual_walk" => hand_r25_mutual_walk(n, black_box(&syms), black_box(lsym)),
            "g25_c_float_prog" => hand_g25_float_prog(n, black_box(0.0)),
            "g25_d_float_next" => {
                let ws: Vec<i64> = (0..len as i64).map(|i| i % 3 + 1).collect();
                hand_g25_float_next(n, black_box(&ws), black_box(1.0e9))
            }
            "r17_c_charge_when" => hand_r17_charge(n),
            "r17_c_courier_global" => hand_r17_courier(n),
            "r17_c_odometer" => hand_r17_odometer(n),
            "r17_c_job_pair" => hand_r17_job_pair(n),
            "r17_d_dock_when" => hand_r17_dock(black_box(lsym), n, black_box(&syms)),
            "r17_d_two_lists" => hand_r17_two_lists(n, black_box(&syms), black_box(lsym)),
            "r17_d_prog_rooms" => hand_r17_prog_rooms(n, black_box(Sym(7))),
            "r17_d_announce" => hand_r17_announce(n, black_box(&syms), black_box(lsym)),
            "r17_d_readings_deep" => {
                let ints: Vec<i64> = (0..len as i64).collect();
                hand_r17_readings(n, black_box(&ints), black_box(len as i64 - 2))
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
        "c_local_count" => ways!(c_local_count),
        "c_local_limit_hop" => ways!(c_local_limit_hop),
        "d_ints_inarg_threshold" => ways!(d_ints_inarg_threshold),
        "d_place_records" => ways!(d_place_records),
        "d_confirm_found" => ways!(d_confirm_found),
        "d_appended_list" => ways!(d_appended_list),
        "c_outarg_apply" => ways!(c_outarg_apply),
        "c_global_flag" => ways!(c_global_flag),
        "d_global_visited" => ways!(d_global_visited),
        "d_outarg_when" => ways!(d_outarg_when),
        "d_room_compounds" => ways!(d_room_compounds),
        "d_pair_key_rest" => ways!(d_pair_key_rest),
        "d_visits_in_id" => ways!(d_visits_in_id),
        "d_first_of_goals" => ways!(d_first_of_goals),
        "d_goto_exit_arc" => ways!(d_goto_exit_arc),
        "d_found_into_next" => ways!(d_found_into_next),
        "c_count_two_levels" => ways!(c_count_two_levels),
        "d_when_arith" => ways!(d_when_arith),
        "c_rec_inarg_pair" => ways!(c_rec_inarg_pair),
        "r18_c_deep_limit" => ways!(r18_c_deep_limit),
        "r18_c_clerk_global" => ways!(r18_c_clerk_global),
        "r18_d_item_qty" => ways!(r18_d_item_qty),
        "r18_d_room_of" => ways!(r18_d_room_of),
        "r18_d_fn_next" => ways!(r18_d_fn_next),
        "r18_d_callee_list" => ways!(r18_d_callee_list),
        "r18_d_yes_no" => ways!(r18_d_yes_no),
        "r18_d_lockstep" => ways!(r18_d_lockstep),
        "r18_d_lockstep_any" => ways!(r18_d_lockstep_any),
        "r17_c_charge_when" => ways!(r17_c_charge_when),
        "r17_c_courier_global" => ways!(r17_c_courier_global),
        "r17_c_odometer" => ways!(r17_c_odometer),
        "r17_c_job_pair" => ways!(r17_c_job_pair),
        "r17_d_dock_when" => ways!(r17_d_dock_when),
        "r17_d_two_lists" => ways!(r17_d_two_lists),
        "r17_d_prog_rooms" => ways!(r17_d_prog_rooms),
        "r17_d_readings_deep" => ways!(r17_d_readings_deep),
        "r17_d_announce" => ways!(r17_d_announce),
        "r19_d_shelves" => ways!(r19_d_shelves),
        "r19_d_collect_out" => ways!(r19_d_collect_out),
        "r19_d_global_goal" => ways!(r19_d_global_goal),
        "r19_c_ping_pong" => ways!(r19_c_ping_pong),
        "r19_d_chain3" => ways!(r19_d_chain3),
        "r19_d_when_qty" => ways!(r19_d_when_qty),
        "r19_d_prolog_first" => ways!(r19_d_prolog_first),
        "c_call_reads_inarg" => ways!(c_call_reads_inarg),
        "r22_d_sweep_say" => ways!(r22_d_sweep_say),
        "r22_d_stock_expect" => ways!(r22_d_stock_expect),
        "r22_d_floor_fn" => ways!(r22_d_floor_fn),
        "r22_d_goal_local" => ways!(r22_d_goal_local),
        "r24_d_gauge_guard" => ways!(r24_d_gauge_guard),
        "r24_d_where_pairs" => ways!(r24_d_where_pairs),
        "r24_d_sift_two_lists" => ways!(r24_d_sift_two_lists),
        "r24_d_near_floats" => ways!(r24_d_near_floats),
        "n24_d_note_walk" => ways!(n24_d_note_walk),
        "r25_d_obj_records" => ways!(r25_d_obj_records),
        "r25_d_prolog_route" => ways!(r25_d_prolog_route),
        "r25_d_filter_out" => ways!(r25_d_filter_out),
        "r25_d_strings" => ways!(r25_d_strings),
        "r25_d_mutual_walk" => ways!(r25_d_mutual_walk),
        "g25_c_float_prog" => ways!(g25_c_float_prog),
        "g25_d_float_next" => ways!(g25_d_float_next),
        "n25_d_float_band" => ways!(n25_d_float_band),
        "n25_d_tally_walk" => ways!(n25_d_tally_walk),
        "c_expr_compare" => ways!(c_expr_compare),
        "g24_d_grow_list" => ways!(g24_d_grow_list),
        _ => unreachable!(),
    }
}

const ALL: [&str; 94] = [
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
    "c_local_count",
    "d_room_compounds",
    "d_pair_key_rest",
    "d_visits_in_id",
    "d_first_of_goals",
    "d_goto_exit_arc",
    "d_found_into_next",
    "c_count_two_levels",
    "d_when_arith",
    "c_rec_inarg_pair",
    "r17_c_charge_when",
    "r17_c_courier_global",
    "r17_c_odometer",
    "r17_c_job_pair",
    "r17_d_dock_when",
    "r17_d_two_lists",
    "r17_d_prog_rooms",
    "r17_d_readings_deep",
    "r17_d_announce",
    "c_call_reads_inarg",
    "c_expr_compare",
    "r18_c_deep_limit",
    "r18_c_clerk_global",
    "r18_d_item_qty",
    "r18_d_room_of",
    "r18_d_fn_next",
    "r18_d_callee_list",
    "r18_d_yes_no",
    "r18_d_lockstep",
    "r18_d_lockstep_any",
    "r19_d_shelves",
    "r19_d_collect_out",
    "r19_c_done_pair",
    "r19_d_global_goal",
    "r19_c_ping_pong",
    "r19_d_chain3",
    "r19_d_when_qty",
    "r19_d_prolog_first",
    "r22_c_stage_global",
    "r22_c_ferry_two",
    "r22_c_lap_pipe",
    "r22_c_rung_id",
    "r22_d_sweep_say",
    "r22_d_stock_expect",
    "r22_d_floor_fn",
    "r22_d_goal_local",
    "r24_c_winch_param",
    "n25_c_tally_grade",
    "r24_c_mill_nested",
    "r24_d_gauge_guard",
    "r24_d_where_pairs",
    "r24_d_sift_two_lists",
    "r24_d_near_floats",
    "n24_d_note_walk",
    "r25_c_pass_limit",
    "r25_c_rota_list",
    "r25_d_obj_records",
    "r25_d_prolog_route",
    "r25_d_filter_out",
    "r25_d_strings",
    "r25_d_mutual_walk",
    "g25_c_float_prog",
    "g25_d_float_next",
    "n25_d_float_band",
    "n25_d_tally_walk",
];

/// The records of `r25_d_obj_records` at `len` places: in the kitchen
/// every third, weights `i % 7 + 1`, the last in the kitchen and the only
/// one above the limit (100 against 50).
fn r25_objs(len: usize) -> Vec<(bool, i64)> {
    (0..len)
        .map(|i| {
            if i + 1 == len {
                (true, 100)
            } else {
                (i % 3 == 0, i as i64 % 7 + 1)
            }
        })
        .collect()
}

/// Whether stop `i` of `r25_d_prolog_route` and `r25_d_filter_out` is
/// `hall`: every fourth from the second, never the last (the target).
fn r25_is_hall(i: usize, len: usize) -> bool {
    i % 4 == 1 && i + 1 != len
}

/// The two lists of `r18_d_lockstep*` at `len` places: `0..len` and a
/// small weight for each (`i % 3 + 1`), the same length.
fn lockstep_lists(len: usize) -> (Vec<i64>, Vec<i64>) {
    let xs = (0..len as i64).collect();
    let ys = (0..len as i64).map(|i| i % 3 + 1).collect();
    (xs, ys)
}

/// The shelves of `r19_d_shelves` at `len` places: `p0..` four a shelf.
fn shelves_text(len: usize) -> String {
    let shelves: Vec<String> = (0..len)
        .collect::<Vec<_>>()
        .chunks(4)
        .map(|c| {
            let items: Vec<String> = c.iter().map(|i| format!("p{i}")).collect();
            format!("[{}]", items.join(","))
        })
        .collect();
    format!("[{}]", shelves.join(","))
}

/// The crates of `r19_d_prolog_first` at `len` places: light weights
/// `0..len - 1`, the last one heavy (1000).
fn crates(len: usize) -> Vec<i64> {
    (0..len as i64)
        .map(|i| if i + 1 == len as i64 { 1000 } else { i })
        .collect()
}

/// Workloads not in [`ALL`] (not in `shapes_table.py`'s run): helper
/// `nglob24`'s global list grown a step, whose cost a transition grows with
/// the steps (its values performed are terms made from the list), measured
/// at 8 and 256 steps instead (docs/guide/performance.md).
const EXTRA: [&str; 1] = ["g24_d_grow_list"];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("check") {
        // `check NAME...`: those workloads only.
        let some: Vec<&str> = args[1..].iter().map(String::as_str).collect();
        for name in ALL
            .into_iter()
            .chain(EXTRA)
            .filter(|n| some.is_empty() || some.contains(n))
        {
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
