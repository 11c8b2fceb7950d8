//! The hand-written Rust machines of the benchmarks' workloads, written
//! once for `benches/benches/compiled.rs` (criterion: the floors of its
//! ratios) and `benches/examples/shapes_prof.rs` (callgrind: the workloads of
//! shapes (c) and (d) of issue 37, and `echo_calls`/`list_search`, the same
//! machines criterion times): each does the work of its workload (atoms an
//! interned index, lists slices, frames on an explicit stack) and returns
//! its transitions, which must be the workload's.
//!
//! Not a module of the library: each of the two includes this file with
//! `#[path]`, and `black_box` is its includer's (`super::black_box`):
//! criterion's in the bench (a volatile read, what its figures were
//! measured with), `std::hint::black_box` in the example, so that neither
//! measures other code than before the machines were moved here. Each
//! includer uses only some of them.
#![allow(dead_code)]

use super::black_box;

/// An atom of the hand-written machines: an interned index (what a Rust
/// `enum` of the places compiles to, for a set of any size).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Sym(pub u32);

/// The hand-written floor for `counter_loop`: the same states, the same
/// counter, the same comparisons, one "transition" per step.
pub fn hand_counter_loop(max: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum St {
        Is,
        Fs,
    }
    let (mut n, mut st, mut transitions) = (0i64, St::Is, 0u64);
    loop {
        transitions += 1;
        match st {
            St::Is => {
                n = black_box(n + 1);
                st = if n >= max { St::Fs } else { St::Is };
            }
            St::Fs => return transitions,
        }
    }
}

/// `hand_counter_loop` handing each new value of the counter to `perform`
/// (a dynamic call per transition, as an effector would be).
pub fn hand_counter_loop_performing(max: i64, perform: &mut dyn FnMut(i64)) -> u64 {
    #[derive(Clone, Copy)]
    enum St {
        Is,
        Fs,
    }
    let (mut n, mut st, mut transitions) = (0i64, St::Is, 0u64);
    loop {
        transitions += 1;
        match st {
            St::Is => {
                n += 1;
                perform(n);
                st = if n >= max { St::Fs } else { St::Is };
            }
            St::Fs => return transitions,
        }
    }
}

/// The hand-written floor for `pipe_calls`: a DM stack of typed frames, the
/// pipe as an integer.
pub fn hand_pipe_calls(max: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Main {
        Call,
        Check,
        Fs,
    }
    #[derive(Clone, Copy)]
    enum AddOne {
        Is,
        Done,
    }
    #[derive(Clone, Copy)]
    enum Frame {
        Main(Main),
        AddOne(AddOne),
    }
    let mut stack: Vec<Frame> = vec![Frame::Main(Main::Call)];
    let (mut pipe, mut transitions) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Main(Main::Call) => stack.push(Frame::AddOne(AddOne::Is)),
            Frame::Main(Main::Check) => {
                transitions += 1;
                *top = Frame::Main(if pipe >= max { Main::Fs } else { Main::Call });
            }
            Frame::Main(Main::Fs) => {
                transitions += 1;
                stack.pop();
            }
            Frame::AddOne(AddOne::Is) => {
                transitions += 1;
                pipe = black_box(pipe + 1);
                *top = Frame::AddOne(AddOne::Done);
            }
            Frame::AddOne(AddOne::Done) => {
                transitions += 1;
                stack.pop();
                // The caller's recursive situation concludes.
                transitions += 1;
                if let Some(Frame::Main(m)) = stack.last_mut() {
                    *m = Main::Check;
                }
            }
        }
    }
    transitions
}

/// The hand-written floor for `echo_calls` (workload c of issue 37): a DM
/// stack of typed frames, the pipe handed to the callee and back, a local
/// counter compared with the limit the recursive situation received.
pub fn hand_echo_calls(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Main {
        Call,
        Fs,
    }
    #[derive(Clone, Copy)]
    enum Echo {
        Is,
        Back,
    }
    #[derive(Clone, Copy)]
    enum Frame {
        Main(Main),
        Echo(Echo),
    }
    let mut stack: Vec<Frame> = vec![Frame::Main(Main::Call)];
    let (mut pipe, mut n, mut transitions) = (limit, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Main(Main::Call) => stack.push(Frame::Echo(Echo::Is)),
            Frame::Main(Main::Fs) => {
                transitions += 1;
                stack.pop();
            }
            Frame::Echo(Echo::Is) => {
                transitions += 1;
                // in_arg X, out_arg X: the pipe goes back as it came.
                pipe = black_box(pipe);
                *top = Frame::Echo(Echo::Back);
            }
            Frame::Echo(Echo::Back) => {
                transitions += 1;
                stack.pop();
                // The caller's recursive situation concludes on `back`.
                transitions += 1;
                n = black_box(n + 1);
                if let Some(Frame::Main(m)) = stack.last_mut() {
                    *m = if n >= pipe { Main::Fs } else { Main::Call };
                }
            }
        }
    }
    transitions
}

/// The hand-written floor for `list_search` (workload d of issue 37):
/// places as symbols, the list walked as a slice, frames on an explicit
/// stack, the callee's final situation carrying the place found.
pub fn hand_list_search(rounds: i64, places: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Main {
        Round,
        Fs,
    }
    #[derive(Clone, Copy)]
    enum Search<'a> {
        Is,
        Try(&'a [Sym]),
        Found(Sym),
        NotFound,
    }
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Main(Main),
        Search(Search<'a>),
    }
    let mut stack: Vec<Frame> = vec![Frame::Main(Main::Round)];
    let (mut n, mut transitions) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Main(Main::Round) => stack.push(Frame::Search(Search::Is)),
            Frame::Main(Main::Fs) => {
                transitions += 1;
                stack.pop();
            }
            Frame::Search(s) => {
                transitions += 1;
                let found = match s {
                    Search::Is => {
                        *top = Frame::Search(Search::Try(places));
                        continue;
                    }
                    Search::Try([]) => {
                        *top = Frame::Search(Search::NotFound);
                        continue;
                    }
                    Search::Try([p, rest @ ..]) => {
                        *top = Frame::Search(if *p == target {
                            Search::Found(*p)
                        } else {
                            Search::Try(rest)
                        });
                        continue;
                    }
                    Search::Found(p) => Some(p),
                    Search::NotFound => None,
                };
                black_box(found);
                stack.pop();
                transitions += 1;
                n = black_box(n + 1);
                if let Some(Frame::Main(m)) = stack.last_mut() {
                    *m = if n >= rounds { Main::Fs } else { Main::Round };
                }
            }
        }
    }
    transitions
}

/// The hand-written floor for `route_walk` (shape d with ints and a nested
/// call): stops as ints walked as a slice, three kinds of frames on an
/// explicit stack, each final carrying its fields to the caller.
pub fn hand_route_walk(trips: i64, stops: &[i64], goal: i64, tag: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Main {
        Trip,
        Done,
    }
    #[derive(Clone, Copy)]
    enum Route {
        Start,
    }
    #[derive(Clone, Copy)]
    enum Walk<'a> {
        Begin,
        Visit(&'a [i64]),
    }
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Main(Main),
        Route(Route),
        Walk(Walk<'a>),
    }
    /// A final's fields, handed to the caller's exit arcs.
    enum Fin {
        At(i64),
        Gone,
        Reached(i64, Sym),
        Lost(Sym),
    }
    let mut stack: Vec<Frame> = vec![Frame::Main(Main::Trip)];
    let (mut k, mut transitions) = (0i64, 0u64);
    let mut fin: Option<Fin> = None;
    while let Some(top) = stack.last_mut() {
        if let Some(f) = fin.take() {
            // The caller's exit arcs on the callee's final.
            transitions += 1;
            match (*top, f) {
                (Frame::Route(Route::Start), Fin::At(s)) => {
                    stack.pop();
                    transitions += 1;
                    fin = Some(Fin::Reached(s, tag));
                }
                (Frame::Route(Route::Start), _) => {
                    stack.pop();
                    transitions += 1;
                    fin = Some(Fin::Lost(tag));
                }
                (Frame::Main(_), f) => {
                    match f {
                        Fin::Reached(s, t) => {
                            black_box((s, t));
                        }
                        Fin::Lost(t) => {
                            black_box(t);
                        }
                        Fin::At(_) | Fin::Gone => unreachable!(),
                    }
                    k = black_box(k + 1);
                    *top = Frame::Main(if k >= trips { Main::Done } else { Main::Trip });
                }
                _ => unreachable!(),
            }
            continue;
        }
        match *top {
            Frame::Main(Main::Trip) => stack.push(Frame::Route(Route::Start)),
            Frame::Main(Main::Done) => {
                transitions += 1;
                stack.pop();
            }
            Frame::Route(Route::Start) => stack.push(Frame::Walk(Walk::Begin)),
            Frame::Walk(w) => {
                transitions += 1;
                match w {
                    Walk::Begin => *top = Frame::Walk(Walk::Visit(stops)),
                    Walk::Visit([]) => {
                        stack.pop();
                        transitions += 1;
                        fin = Some(Fin::Gone);
                    }
                    Walk::Visit([s, rest @ ..]) => {
                        if *s == goal {
                            stack.pop();
                            transitions += 1;
                            fin = Some(Fin::At(*s));
                        } else {
                            *top = Frame::Walk(Walk::Visit(rest));
                        }
                    }
                }
            }
        }
    }
    transitions
}

/// The hand-written floor for `count_pipe` (shape c with a nested call and
/// a parameter): the pipe an int handed to the innermost callee and back,
/// three kinds of frames on an explicit stack.
pub fn hand_count_pipe(max: i64, step: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Go,
        Stop,
        Hop,
        Bounce,
        Back,
        Passed(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Go];
    let (mut pipe, mut count, mut transitions) = (max, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Go => stack.push(Frame::Hop),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Hop => stack.push(Frame::Bounce),
            Frame::Bounce => {
                transitions += 1;
                // in_arg X, out_arg X: the pipe goes back as it came.
                pipe = black_box(pipe);
                *top = Frame::Back;
            }
            Frame::Back => {
                transitions += 2;
                stack.pop();
                // relay's exit arc: `back` => passed(Step).
                if let Some(t) = stack.last_mut() {
                    *t = Frame::Passed(step);
                }
            }
            Frame::Passed(s) => {
                transitions += 2;
                black_box(s);
                stack.pop();
                count = black_box(count + 1);
                if let Some(t) = stack.last_mut() {
                    *t = if count >= pipe {
                        Frame::Stop
                    } else {
                        Frame::Go
                    };
                }
            }
        }
    }
    transitions
}

/// The hand-written floor for `scripted_loop`: the same script read line by
/// line, each input compared with the expectations as text (no term is
/// parsed), the counter an integer.
pub fn hand_scripted_loop(script: &str) -> u64 {
    #[derive(Clone, Copy)]
    enum St {
        Is,
        Fs,
    }
    let (mut n, mut st, mut transitions) = (0i64, St::Is, 0u64);
    let mut lines = script.lines();
    loop {
        match st {
            St::Is => {
                let input = lines.next().map(|l| l.trim().trim_end_matches('.'));
                transitions += 1;
                match input {
                    Some("tick") => n = black_box(n + 1),
                    Some("stop") => st = St::Fs,
                    _ => return transitions,
                }
            }
            St::Fs => return transitions + 1,
        }
    }
}

/// (c) with the limit in the pipe: `depth` 1 (the callee hands the pipe
/// back) or 2 (a DM between, passing it through); the count in the
/// caller's id, a local or the callee's parameter (all an `i64` here).
/// `start`: the caller's first situation setting the pipe.
pub fn hand_echo(limit: i64, depth: u32, cond_out: bool) -> u64 {
    hand_echo_as(limit, depth, cond_out, false)
}

/// [`hand_echo`] with the limit a float (`float`: the count, an int,
/// compared with it as the machine compares an int with a float).
pub fn hand_echo_as(limit: i64, depth: u32, cond_out: bool, float: bool) -> u64 {
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
pub enum Exit<'a, T> {
    Found(T),
    FoundRest(T, &'a [T]),
    NotFound,
}

/// (d): `rounds` calls of a walk over `items` for `target`, the list a
/// slice, the element compared by `==`; `start`: the caller's first
/// situation (one transition); `rest`: the final hands back the rest.
pub fn hand_walk<T: Copy + PartialEq>(
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
pub fn hand_walk_seen(rounds: i64, items: &[Sym], target: Sym) -> u64 {
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

/// (c) with the callee computing its out_arg (`c_outarg_apply`: the pipe
/// plus one, which the workload's Prolog user function `succ_of/1`
/// computes: here a Rust addition, so the ratio is not like with like),
/// the caller comparing the pipe with the limit on a neutral situation.
pub fn hand_succ(limit: i64) -> u64 {
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
pub fn hand_walk_pairs(rounds: i64, pairs: &[(Sym, Sym)], item: Sym) -> u64 {
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
pub fn hand_pair(limit: i64) -> u64 {
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

/// (c) `c_rec_inarg_pair`: the pipe a pair (count, limit) set once, read
/// by the recursive situation itself before each call (its in_arg
/// pattern, the values kept in its waiting frame), the callee counting and
/// handing both back, the exit arc comparing the count read with the
/// limit.
pub fn hand_rec_pair(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask,
        Wait(i64, i64),
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
                pipe = black_box((1, limit));
                *top = Frame::Ask;
            }
            Frame::Ask => {
                let (n, l) = pipe;
                *top = Frame::Wait(n, l);
                stack.push(Frame::Step);
            }
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
                    if let Frame::Wait(n, l) = *m {
                        *m = if n < l { Frame::Ask } else { Frame::Over };
                    }
                }
            }
            Frame::Wait(..) => unreachable!("a waiting frame is never on top"),
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (c) `c_call_reads_inarg`: the count in the pipe, read by the recursive
/// situation's in_arg and given to the call only (an argument of the
/// callee's frame), the limit in the caller's id; the callee counts, hands
/// the count back in the pipe and ends in `more` or `done` by comparing
/// it with the limit, which the caller's exit arcs match.
pub fn hand_call_reads_inarg(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask(i64),
        Wait(i64),
        Over,
        Step(i64, i64),
        More,
        Done,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut transitions) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                pipe = black_box(0);
                *top = Frame::Ask(limit);
            }
            Frame::Ask(lim) => {
                let n = pipe;
                *top = Frame::Wait(lim);
                stack.push(Frame::Step(n, lim));
            }
            Frame::Step(n, lim) => {
                transitions += 1;
                let m = n + 1;
                pipe = black_box(m);
                *top = if m < lim { Frame::More } else { Frame::Done };
            }
            Frame::More | Frame::Done => {
                // The callee's final, then the caller's exit arc.
                let more = matches!(*top, Frame::More);
                transitions += 2;
                stack.pop();
                if let Some(w) = stack.last_mut() {
                    if let Frame::Wait(lim) = *w {
                        *w = if more { Frame::Ask(lim) } else { Frame::Over };
                    }
                }
            }
            Frame::Wait(_) => unreachable!("a waiting frame is never on top"),
            Frame::Over => {
                transitions += 1;
                stack.pop();
            }
        }
    }
    transitions
}

/// (c) `c_expr_compare`: the count in the caller's waiting frame, the
/// callee one step, the exit arc comparing two expressions (`J * 2 <
/// Max * 2`) computed in Rust.
pub fn hand_expr_compare(max: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Ask(i64),
        Wait(i64),
        Over,
        Step,
        Ticked,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let mut transitions = 0u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                transitions += 1;
                *top = Frame::Ask(0);
            }
            Frame::Ask(i) => {
                *top = Frame::Wait(i);
                stack.push(Frame::Step);
            }
            Frame::Step => {
                transitions += 1;
                *top = Frame::Ticked;
            }
            Frame::Ticked => {
                // The callee's final, then the caller's exit arc.
                transitions += 2;
                stack.pop();
                if let Some(w) = stack.last_mut() {
                    if let Frame::Wait(i) = *w {
                        let j = black_box(i + 1);
                        *w = if j * 2 < max * 2 {
                            Frame::Ask(j)
                        } else {
                            Frame::Over
                        };
                    }
                }
            }
            Frame::Wait(_) => unreachable!("a waiting frame is never on top"),
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
pub fn hand_final_by_inarg(limit: i64) -> u64 {
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

/// (c) `c_local_count`: N calls of a callee that counts its own local
/// (0 at each call) into the pipe, the caller counting the calls in its
/// own local (the id `next(C)`) and comparing the count with the limit.
/// Each frame holds its DM's local beside its situation.
pub fn hand_local_count(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Ask,
        Next(i64),
        Over,
        Go,
        Done,
    }
    let mut stack: Vec<(Frame, i64)> = vec![(Frame::Ask, 0)];
    let (mut pipe, mut transitions) = (0i64, 0u64);
    while let Some((top, local)) = stack.last_mut() {
        match *top {
            Frame::Ask => stack.push((Frame::Go, 0)),
            Frame::Go => {
                transitions += 1;
                *local += 1;
                pipe = black_box(*local);
                *top = Frame::Done;
            }
            Frame::Done => {
                // The callee's final, then the caller's exit arc.
                transitions += 2;
                stack.pop();
                if let Some((m, calls)) = stack.last_mut() {
                    *calls += 1;
                    *m = Frame::Next(black_box(*calls));
                }
            }
            Frame::Next(c) => {
                transitions += 1;
                *top = if c < limit { Frame::Ask } else { Frame::Over };
            }
            Frame::Over => {
                transitions += 1;
                black_box(pipe);
                stack.pop();
            }
        }
    }
    transitions
}

/// (c) `c_local_limit_hop`: the limit a local, the count in the pipe,
/// incremented two levels down, passed through `hop`'s neutral situation.
pub fn hand_local_limit_hop(limit: i64) -> u64 {
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
pub fn hand_walk_by<T: Copy, R: Copy>(
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
pub fn hand_walk_confirm(rounds: i64, items: &[Sym], target: Sym, unknown: Sym) -> u64 {
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
pub fn hand_flag(limit: i64) -> u64 {
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
pub fn hand_walk_visited(budget: i64, items: &[Sym], target: Sym) -> u64 {
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
pub fn hand_walk_flag(rounds: i64, items: &[Sym], target: Sym) -> u64 {
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

// Helper `nsurvey16`'s (session 15).

/// A place as the compound `room(Name)` of `d_room_compounds`: a newtype
/// of its name (what a typed field of one functor compiles to).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Room(pub Sym);

/// (d) `d_visits_in_id`: the walk counts the places it visits in its
/// frame (`try(Ps, K)`) and hands the count back; the caller adds it to
/// a total kept in its frame (`round(I, Total)`).
pub fn hand_walk_count(rounds: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round(i64, i64),
        Stop,
        Begin,
        Try(&'a [Sym], i64),
        Final(bool, i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round(0, 0)];
    let mut transitions = 1u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round(..) => stack.push(Frame::Begin),
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Try(items, 0);
            }
            Frame::Try([], k) => {
                transitions += 1;
                *top = Frame::Final(false, k);
            }
            Frame::Try([p, ps @ ..], k) => {
                transitions += 1;
                let k1 = black_box(k + 1);
                *top = if *p == target {
                    Frame::Final(true, k1)
                } else {
                    Frame::Try(ps, k1)
                };
            }
            Frame::Final(found, k) => {
                transitions += 2;
                black_box(found);
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    if let Frame::Round(i, total) = *m {
                        let (j, t) = (black_box(i + 1), black_box(total + k));
                        *m = if j < rounds {
                            Frame::Round(j, t)
                        } else {
                            Frame::Stop
                        };
                    }
                }
            }
        }
    }
    transitions
}

/// (d) `d_goto_exit_arc`: the walk calls a one-step DM per place
/// (`goto(P)`, ending in `arrived(P)`), whose exit arc in the walking
/// frame compares the place reached with the target.
pub fn hand_walk_goto(rounds: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Visit(&'a [Sym]),
        Move(Sym),
        Arrived(Sym),
        Final(Option<Sym>),
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
                *top = Frame::Visit(items);
            }
            Frame::Visit([]) => {
                transitions += 1;
                *top = Frame::Final(None);
            }
            Frame::Visit([p, ..]) => stack.push(Frame::Move(*p)),
            Frame::Move(p) => {
                transitions += 1;
                *top = Frame::Arrived(p);
            }
            Frame::Arrived(q) => {
                // `goto`'s final, then the walking situation's exit arc.
                transitions += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    if let Frame::Visit([_, ps @ ..]) = *m {
                        *m = if q == target {
                            Frame::Final(Some(q))
                        } else {
                            Frame::Visit(ps)
                        };
                    }
                }
            }
            Frame::Final(found) => {
                transitions += 2;
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

/// (d) `d_found_into_next`: the caller's exit arc binds the place found
/// into its next frame (`seen(P, I)`), one more step that reads it (a
/// walk that found nothing stops the run).
pub fn hand_walk_seen_next(rounds: i64, items: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round(i64),
        Seen(Option<Sym>, i64),
        Stop,
        Begin,
        Walk(&'a [Sym]),
        Final(Option<Sym>),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round(0)];
    let mut transitions = 1u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round(_) => stack.push(Frame::Begin),
            Frame::Seen(p, i) => {
                transitions += 1;
                let j = black_box(i + 1);
                *top = match p {
                    Some(_) if j < rounds => Frame::Round(j),
                    _ => Frame::Stop,
                };
            }
            Frame::Stop => {
                transitions += 1;
                stack.pop();
            }
            Frame::Begin => {
                transitions += 1;
                *top = Frame::Walk(items);
            }
            Frame::Walk([]) => {
                transitions += 1;
                *top = Frame::Final(None);
            }
            Frame::Walk([p, ps @ ..]) => {
                transitions += 1;
                *top = if *p == target {
                    Frame::Final(Some(*p))
                } else {
                    Frame::Walk(ps)
                };
            }
            Frame::Final(found) => {
                transitions += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    if let Frame::Round(i) = *m {
                        *m = Frame::Seen(black_box(found), i);
                    }
                }
            }
        }
    }
    transitions
}

/// (c) `c_count_two_levels`: the count handed back through two levels of
/// finals (`inner`'s `done(M)`, `outer`'s `back(M)`), each level a frame
/// holding it; the caller compares it with the limit.
pub fn hand_two_levels(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Call(i64),
        Over,
        Ask(i64),
        Back(i64),
        Step(i64),
        Done(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Call(0)];
    let mut transitions = 1u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Call(n) => stack.push(Frame::Ask(n)),
            Frame::Ask(n) => stack.push(Frame::Step(n)),
            Frame::Step(n) => {
                transitions += 1;
                *top = Frame::Done(black_box(n + 1));
            }
            Frame::Done(m) => {
                // `inner`'s final, then `outer`'s exit arc.
                transitions += 2;
                stack.pop();
                if let Some(o) = stack.last_mut() {
                    *o = Frame::Back(m);
                }
            }
            Frame::Back(m) => {
                // `outer`'s final, then `relay`'s exit arc.
                transitions += 2;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = if black_box(m) < limit {
                        Frame::Call(m)
                    } else {
                        Frame::Over
                    };
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

/// (d) `d_when_arith`: a walk over all of `items` (ints) whose every
/// walking step sets the pipe to `found(X)` when the item is above `limit`,
/// else `none` (the out_arg `apply(when(_, _, _), [X > Limit, found(X),
/// none])`; an `Option<i64>` here, `black_box`ed where written), the walk
/// ending in `done`.
pub fn hand_walk_when_arith(rounds: i64, items: &[i64], limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Begin,
        Try(&'a [i64]),
        Done,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut transitions, mut pipe) = (0i64, 1u64, None);
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
                *top = Frame::Done;
            }
            Frame::Try([x, xs @ ..]) => {
                transitions += 1;
                pipe = black_box((*x > limit).then_some(*x));
                *top = Frame::Try(xs);
            }
            Frame::Done => {
                transitions += 1;
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
    black_box(pipe);
    transitions
}

// Helper `review17`'s (session 16): workloads written without reading
// `tests/typed/shapes/` (`tests/typed/review17/`).

/// (c) `r17_c_charge_when`: the limit put in the pipe by the first
/// situation, taken by the recursive situation's in_arg (kept in its
/// frame), the callee's two steps handing the pipe back, the count a
/// local of the caller.
pub fn hand_r17_charge(full: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Plug,
        Cycle,
        Unplug,
        Sense(i64),
        Idle(i64),
        Full(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Plug];
    let (mut pipe, mut cycles, mut t) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Plug => {
                t += 1;
                pipe = black_box(full);
                *top = Frame::Cycle;
            }
            // in_arg Cap: the pipe as the call starts, kept by the callee's
            // frames for the exit arc.
            Frame::Cycle => stack.push(Frame::Sense(pipe)),
            Frame::Sense(cap) => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Idle(cap);
            }
            Frame::Idle(cap) => {
                t += 1;
                *top = Frame::Full(cap);
            }
            Frame::Full(cap) => {
                t += 2;
                stack.pop();
                cycles = black_box(cycles + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if cycles >= cap {
                        Frame::Unplug
                    } else {
                        Frame::Cycle
                    };
                }
            }
            Frame::Unplug => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r17_c_courier_global`: three levels of frames, the pipe handed
/// back by the innermost, the trips done a global (an `i64` here).
pub fn hand_r17_courier(trips: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Brief,
        Go,
        Rest,
        Leave(i64),
        Give(i64),
        Passed(i64),
        Delivered(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Brief];
    let (mut pipe, mut done, mut t) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Brief => {
                t += 1;
                pipe = black_box(trips);
                *top = Frame::Go;
            }
            Frame::Go => stack.push(Frame::Leave(pipe)),
            Frame::Leave(lim) => stack.push(Frame::Give(lim)),
            Frame::Give(lim) => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Passed(lim);
            }
            Frame::Passed(lim) => {
                // `handoff`'s final, `courier`'s exit arc.
                t += 2;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = Frame::Delivered(lim);
                }
            }
            Frame::Delivered(lim) => {
                // `courier`'s final, `mission`'s exit arc.
                t += 2;
                stack.pop();
                done = black_box(done + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if done >= lim { Frame::Rest } else { Frame::Go };
                }
            }
            Frame::Rest => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r17_c_odometer`: the callee adds one to the pipe and hands it
/// back in its final situation's id too; the caller's exit arc compares it
/// with its parameter.
pub fn hand_r17_odometer(laps: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Lap,
        Park,
        Tick,
        Moved(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                pipe = black_box(0);
                *top = Frame::Lap;
            }
            Frame::Lap => stack.push(Frame::Tick),
            Frame::Tick => {
                t += 1;
                pipe = black_box(pipe + 1);
                *top = Frame::Moved(pipe);
            }
            Frame::Moved(m) => {
                t += 2;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = if m >= laps { Frame::Park } else { Frame::Lap };
                }
            }
            Frame::Park => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r17_c_job_pair`: the pipe a pair of ints (`job(Left, Done)`), the
/// callee counting one down and the other up, the caller reading it in
/// the situation after the call.
pub fn hand_r17_job_pair(n: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Open,
        Work,
        Fork,
        Close,
        Punch,
        Clocked,
    }
    let mut stack: Vec<Frame> = vec![Frame::Open];
    let (mut pipe, mut t) = ((0i64, 0i64), 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Open => {
                t += 1;
                pipe = black_box((n, 0));
                *top = Frame::Work;
            }
            Frame::Work => stack.push(Frame::Punch),
            Frame::Punch => {
                t += 1;
                let (l, d) = pipe;
                pipe = black_box((l - 1, d + 1));
                *top = Frame::Clocked;
            }
            Frame::Clocked => {
                t += 2;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = Frame::Fork;
                }
            }
            Frame::Fork => {
                t += 1;
                *top = if pipe.0 <= 0 {
                    Frame::Close
                } else {
                    Frame::Work
                };
            }
            Frame::Close => {
                t += 1;
                stack.pop();
            }
        }
    }
    black_box(pipe);
    t
}

/// (d) `r17_d_dock_when`: the walk of [`hand_list_search`], the exit arc
/// comparing the place found with the caller's own target and counting in
/// a local.
pub fn hand_r17_dock(target: Sym, rounds: i64, docks: &[Sym]) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Dispatch,
        Halt,
        Begin,
        Probe(&'a [Sym]),
        At(Sym),
        Missing,
    }
    let mut stack: Vec<Frame> = vec![Frame::Dispatch];
    let (mut done, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Dispatch => stack.push(Frame::Begin),
            Frame::Halt => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Probe(docks);
            }
            Frame::Probe([]) => {
                t += 1;
                *top = Frame::Missing;
            }
            Frame::Probe([d, rest @ ..]) => {
                t += 1;
                *top = if *d == target {
                    Frame::At(*d)
                } else {
                    Frame::Probe(rest)
                };
            }
            Frame::At(d) => {
                t += 2;
                stack.pop();
                done = black_box(done + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if d == target && done < rounds {
                        Frame::Dispatch
                    } else {
                        Frame::Halt
                    };
                }
            }
            Frame::Missing => {
                t += 2;
                stack.pop();
                done = black_box(done + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if done < rounds {
                        Frame::Dispatch
                    } else {
                        Frame::Halt
                    };
                }
            }
        }
    }
    t
}

/// (d) `r17_d_two_lists`: the walk keeps the places seen (a vector reused
/// from round to round, one push a visit) and hands them back with the
/// place found.
pub fn hand_r17_two_lists(rounds: i64, shelves: &[Sym], item: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Check,
        Report,
        Start,
        Pass(&'a [Sym]),
        Spotted(Sym),
        Absent,
    }
    let mut stack: Vec<Frame> = vec![Frame::Check];
    let mut seen: Vec<Sym> = Vec::with_capacity(shelves.len());
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Check => stack.push(Frame::Start),
            Frame::Report => {
                t += 1;
                stack.pop();
            }
            Frame::Start => {
                t += 1;
                seen.clear();
                *top = Frame::Pass(shelves);
            }
            Frame::Pass([]) => {
                t += 1;
                *top = Frame::Absent;
            }
            Frame::Pass([s, ss @ ..]) => {
                t += 1;
                *top = if *s == item {
                    Frame::Spotted(*s)
                } else {
                    seen.push(*s);
                    Frame::Pass(ss)
                };
            }
            Frame::Spotted(s) => {
                t += 2;
                black_box((s, &seen));
                stack.pop();
                n = black_box(n + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if n >= rounds {
                        Frame::Report
                    } else {
                        Frame::Check
                    };
                }
            }
            Frame::Absent => {
                // `absent([])` only: a non-empty walk that found nothing
                // is the run's error.
                t += 1;
                if !seen.is_empty() {
                    return t;
                }
                t += 1;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = Frame::Report;
                }
            }
        }
    }
    t
}

/// (d) `r17_d_prog_rooms`: a constant list of rooms set by the walk's
/// first situation, the visits counted in the walk's frame and handed back
/// in its final, the rounds counted by the caller.
pub fn hand_r17_prog_rooms(rounds: i64, goal: Sym) -> u64 {
    const ROOMS: [Sym; 8] = [
        Sym(0),
        Sym(1),
        Sym(2),
        Sym(3),
        Sym(4),
        Sym(5),
        Sym(6),
        Sym(7),
    ];
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Home,
        Load,
        Room(&'a [Sym], i64),
        There(Sym, i64),
        Nowhere(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut laps, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Load),
            Frame::Home => {
                t += 1;
                stack.pop();
            }
            Frame::Load => {
                t += 1;
                *top = Frame::Room(black_box(&ROOMS[..]), 0);
            }
            Frame::Room([], v) => {
                t += 1;
                *top = Frame::Nowhere(v);
            }
            Frame::Room([r, rs @ ..], v) => {
                t += 1;
                let v = black_box(v + 1);
                *top = if *r == goal {
                    Frame::There(*r, v)
                } else {
                    Frame::Room(rs, v)
                };
            }
            Frame::There(..) | Frame::Nowhere(_) => {
                t += 2;
                black_box(*top);
                stack.pop();
                laps = black_box(laps + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if laps >= rounds {
                        Frame::Home
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (d) `r17_d_readings_deep`: a walk over ints three frames deep, each
/// final turned into the caller's (`high(R)` to `alarm(R)`).
pub fn hand_r17_readings(rounds: i64, readings: &[i64], limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Poll,
        Off,
        Read,
        Go,
        Chk(&'a [i64]),
        High(i64),
        Low,
        Alarm(i64),
        Calm,
    }
    let mut stack: Vec<Frame> = vec![Frame::Poll];
    let (mut polls, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Poll => stack.push(Frame::Read),
            Frame::Off => {
                t += 1;
                stack.pop();
            }
            Frame::Read => stack.push(Frame::Go),
            Frame::Go => {
                t += 1;
                *top = Frame::Chk(readings);
            }
            Frame::Chk([]) => {
                t += 1;
                *top = Frame::Low;
            }
            Frame::Chk([r, rest @ ..]) => {
                t += 1;
                *top = if *r > limit {
                    Frame::High(*r)
                } else {
                    Frame::Chk(rest)
                };
            }
            Frame::High(_) | Frame::Low => {
                t += 2;
                let fin = *top;
                stack.pop();
                if let Some(c) = stack.last_mut() {
                    *c = match fin {
                        Frame::High(r) => Frame::Alarm(r),
                        _ => Frame::Calm,
                    };
                }
            }
            Frame::Alarm(_) | Frame::Calm => {
                t += 2;
                black_box(*top);
                stack.pop();
                polls = black_box(polls + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if polls >= rounds {
                        Frame::Off
                    } else {
                        Frame::Poll
                    };
                }
            }
        }
    }
    t
}

/// (d) `r17_d_announce`: [`hand_list_search`]'s walk, each place passed
/// handed to the effector (`black_box`: the action no effector declares
/// does nothing).
pub fn hand_r17_announce(rounds: i64, spots: &[Sym], goal: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Go,
        Stop,
        Is,
        At(&'a [Sym]),
        Reached(Sym),
        Lost,
    }
    let mut stack: Vec<Frame> = vec![Frame::Go];
    let (mut k, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Go => stack.push(Frame::Is),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::Is => {
                t += 1;
                *top = Frame::At(spots);
            }
            Frame::At([]) => {
                t += 1;
                *top = Frame::Lost;
            }
            Frame::At([s, ss @ ..]) => {
                t += 1;
                black_box(*s);
                *top = if *s == goal {
                    Frame::Reached(*s)
                } else {
                    Frame::At(ss)
                };
            }
            Frame::Reached(_) | Frame::Lost => {
                t += 2;
                stack.pop();
                k = black_box(k + 1);
                if let Some(c) = stack.last_mut() {
                    *c = if k >= rounds { Frame::Stop } else { Frame::Go };
                }
            }
        }
    }
    t
}

/// (c) `r18_c_deep_limit` (helper `review18`): three DMs deep, the limit
/// in the pipe handed back by the deepest callee, the calls counted in a
/// global the middle DM increments and hands up in its final's id.
pub fn hand_r18_deep_limit(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Call,
        Fs,
        Down,
        Back(i64),
        Echo,
        Up,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut trips, mut t) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                pipe = black_box(limit);
                *top = Frame::Call;
            }
            // The recursive situation reads the pipe (its in_arg) and calls.
            Frame::Call => stack.push(Frame::Down),
            Frame::Down => stack.push(Frame::Echo),
            Frame::Echo => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Up;
            }
            Frame::Up => {
                // `leaf`'s final, `relay`'s exit arc (`inc(trips, K)`).
                t += 2;
                stack.pop();
                trips = black_box(trips + 1);
                if let Some(r) = stack.last_mut() {
                    *r = Frame::Back(trips);
                }
            }
            Frame::Back(k) => {
                // `relay`'s final, `top`'s exit arc.
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if k >= pipe { Frame::Fs } else { Frame::Call };
                }
            }
            Frame::Fs => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r18_c_clerk_global`: the callee counts in a global, compares it
/// with its parameter and picks its final (`more` or `enough(S)`), which
/// the caller's exit arcs match.
pub fn hand_r18_clerk(max: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Ask,
        Done(i64),
        Serve(i64),
        More,
        Enough(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Ask];
    let (mut served, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Ask => stack.push(Frame::Serve(max)),
            Frame::Serve(limit) => {
                t += 1;
                served = black_box(served + 1);
                *top = if served >= limit {
                    Frame::Enough(served)
                } else {
                    Frame::More
                };
            }
            Frame::More | Frame::Enough(_) => {
                let f = *top;
                t += 2;
                stack.pop();
                if let Some(b) = stack.last_mut() {
                    *b = match f {
                        Frame::Enough(s) => Frame::Done(s),
                        _ => Frame::Ask,
                    };
                }
            }
            Frame::Done(s) => {
                t += 1;
                black_box(s);
                stack.pop();
            }
        }
    }
    t
}

/// An inventory line of `r18_d_item_qty`: `item(Name, Qty)`.
#[derive(Clone, Copy)]
pub struct Item(pub Sym, pub i64);

/// (d) `r18_d_item_qty`: a walk over `item(Name, Qty)` records adding up
/// the quantities before the one wanted; the final carries two ints.
pub fn hand_r18_item_qty(rounds: i64, items: &[Item], want: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Fs,
        Begin,
        Look(&'a [Item], i64),
        Have(i64, i64),
        None(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Fs => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Look(items, 0);
            }
            Frame::Look([], sum) => {
                t += 1;
                *top = Frame::None(sum);
            }
            Frame::Look([Item(name, qty), rest @ ..], sum) => {
                t += 1;
                let sum1 = sum + qty;
                *top = if *name == want {
                    Frame::Have(*qty, sum)
                } else {
                    Frame::Look(rest, sum1)
                };
            }
            f @ (Frame::Have(..) | Frame::None(_)) => {
                t += 2;
                black_box(match f {
                    Frame::Have(q, b) => (q, b),
                    Frame::None(s) => (-1, s),
                    _ => unreachable!(),
                });
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds { Frame::Fs } else { Frame::Round };
                }
            }
        }
    }
    t
}

/// (d) `r18_d_room_of`: `Room-Object` pairs, the object matched (the id's
/// second clause), the room handed back and compared with the expected
/// one (`moved(R)` one more transition when it differs).
pub fn hand_r18_room_of(rounds: i64, pairs: &[(Sym, Sym)], obj: Sym, home: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Fs(Option<Sym>),
        Moved(Sym),
        Begin,
        Scan(&'a [(Sym, Sym)]),
        In(Sym),
        Lost,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Fs(r) => {
                t += 1;
                black_box(r);
                stack.pop();
            }
            Frame::Moved(r) => {
                t += 1;
                black_box(r);
                *top = Frame::Round;
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Scan(pairs);
            }
            Frame::Scan([]) => {
                t += 1;
                *top = Frame::Lost;
            }
            Frame::Scan([(room, o), rest @ ..]) => {
                t += 1;
                *top = if *o == obj {
                    Frame::In(*room)
                } else {
                    Frame::Scan(rest)
                };
            }
            f @ (Frame::In(_) | Frame::Lost) => {
                t += 2;
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = match f {
                        Frame::In(r) if n >= rounds => Frame::Fs(Some(r)),
                        Frame::In(r) if r == home => Frame::Round,
                        Frame::In(r) => Frame::Moved(r),
                        _ if n >= rounds => Frame::Fs(None),
                        _ => Frame::Round,
                    };
                }
            }
        }
    }
    t
}

/// (d) `r18_d_lockstep`: two lists of ints walked in step, a dot product
/// in the id; `uneven` when one ends first; the sum compared with `min`
/// (`low(S)` one more transition below it).
pub fn hand_r18_lockstep(rounds: i64, xs: &[i64], ys: &[i64], min: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Fs(Option<i64>),
        Low(i64),
        Begin,
        Step(&'a [i64], &'a [i64], i64),
        Sum(i64),
        Uneven,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Fs(s) => {
                t += 1;
                black_box(s);
                stack.pop();
            }
            Frame::Low(s) => {
                t += 1;
                black_box(s);
                *top = Frame::Round;
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Step(xs, ys, 0);
            }
            Frame::Step([], [], acc) => {
                t += 1;
                *top = Frame::Sum(acc);
            }
            Frame::Step([x, xs1 @ ..], [y, ys1 @ ..], acc) => {
                t += 1;
                *top = Frame::Step(xs1, ys1, acc + x * y);
            }
            Frame::Step(..) => {
                t += 1;
                *top = Frame::Uneven;
            }
            f @ (Frame::Sum(_) | Frame::Uneven) => {
                t += 2;
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = match f {
                        Frame::Sum(s) if n >= rounds => Frame::Fs(Some(s)),
                        Frame::Sum(s) if s >= min => Frame::Round,
                        Frame::Sum(s) => Frame::Low(s),
                        _ if n >= rounds => Frame::Fs(None),
                        _ => Frame::Round,
                    };
                }
            }
        }
    }
    t
}

/// (d) `r18_d_callee_list`: the callee reverses the stops into a route
/// (a new list a round: a `Vec` here, its allocation reused) that the
/// caller then walks in its own situations looking for the dock.
pub fn hand_r18_callee_list(rounds: i64, stops: &[Sym], dock: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Go(usize),
        Docked,
        Fs,
        Begin,
        Rev(&'a [Sym]),
        Route,
    }
    let mut route: Vec<Sym> = Vec::with_capacity(stops.len());
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                route.clear();
                *top = Frame::Rev(stops);
            }
            Frame::Rev([]) => {
                t += 1;
                route.reverse();
                *top = Frame::Route;
            }
            Frame::Rev([s, ss @ ..]) => {
                t += 1;
                route.push(black_box(*s));
                *top = Frame::Rev(ss);
            }
            Frame::Route => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Go(0);
                }
            }
            Frame::Go(i) => {
                t += 1;
                *top = match route.get(i) {
                    Some(&s) if s == dock => Frame::Docked,
                    Some(_) => Frame::Go(i + 1),
                    None => {
                        n = black_box(n + 1);
                        if n >= rounds {
                            Frame::Fs
                        } else {
                            Frame::Round
                        }
                    }
                };
            }
            Frame::Docked => {
                t += 1;
                n = black_box(n + 1);
                *top = if n >= rounds { Frame::Fs } else { Frame::Round };
            }
            Frame::Fs => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r18_d_yes_no`: a walk asking at each place; the answers read from
/// a script (one `yes.` or `no.` a line), as `hand_scripted_loop` reads
/// its own.
pub fn hand_r18_yes_no(rounds: i64, places: &[Sym], script: &str) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Fs,
        Begin,
        Q(&'a [Sym]),
        Found(Sym),
        Nowhere,
    }
    let mut lines = script.lines();
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Begin),
            Frame::Fs => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Q(places);
            }
            Frame::Q([]) => {
                t += 1;
                *top = Frame::Nowhere;
            }
            Frame::Q([p, ps @ ..]) => {
                t += 1;
                let said = lines.next().map(|l| l.trim().trim_end_matches('.'));
                *top = match said {
                    Some("yes") => Frame::Found(*p),
                    Some("no") => Frame::Q(ps),
                    _ => return t,
                };
            }
            f @ (Frame::Found(_) | Frame::Nowhere) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds { Frame::Fs } else { Frame::Round };
                }
            }
        }
    }
    t
}

/// (d) `r19_d_shelves` (helper `review19`): a list of lists, the shelves
/// walked and the items of each shelf walked, two kinds of frame state for
/// the two ids; `got(Item)` or `none` back to the caller.
pub fn hand_r19_shelves(rounds: i64, shelves: &[Vec<Sym>], want: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Enter,
        Shelf(&'a [Vec<Sym>]),
        Item(&'a [Sym], &'a [Vec<Sym>]),
        Got(Sym),
        None,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Enter),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::Enter => {
                t += 1;
                *top = Frame::Shelf(shelves);
            }
            Frame::Shelf([]) => {
                t += 1;
                *top = Frame::None;
            }
            Frame::Shelf([s, ss @ ..]) => {
                t += 1;
                *top = Frame::Item(s, ss);
            }
            Frame::Item([], ss) => {
                t += 1;
                *top = Frame::Shelf(ss);
            }
            Frame::Item([i, is @ ..], ss) => {
                t += 1;
                *top = if *i == want {
                    Frame::Got(*i)
                } else {
                    Frame::Item(is, ss)
                };
            }
            f @ (Frame::Got(_) | Frame::None) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (d) `r19_d_collect_out` (helper `review19`): the readings above `limit`
/// gathered in a round (a `Vec`, its allocation reused, the newest first
/// as the DM's `[R|Acc]`) and handed back as the pipe; the last round's
/// list is the final situation's in_arg.
pub fn hand_r19_collect_out(rounds: i64, readings: &[i64], limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Start,
        Pass(&'a [i64]),
        Kept,
    }
    let mut acc: Vec<i64> = Vec::with_capacity(readings.len());
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Start),
            Frame::Stop => {
                t += 1;
                black_box(&acc);
                stack.pop();
            }
            Frame::Start => {
                t += 1;
                acc.clear();
                *top = Frame::Pass(readings);
            }
            Frame::Pass([]) => {
                t += 1;
                // out_arg ==> Acc: the newest first.
                acc.reverse();
                *top = Frame::Kept;
            }
            Frame::Pass([r, rs @ ..]) => {
                t += 1;
                if *r > limit {
                    acc.push(*r);
                }
                *top = Frame::Pass(rs);
            }
            Frame::Kept => {
                t += 2;
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (c) `r19_c_done_pair` (helper `review19`): `echo_calls` with a final
/// carrying a pair, `done(X, tick)`, the caller matching its tag and
/// comparing its count with the pair's first field.
pub fn hand_r19_done_pair(limit: i64) -> u64 {
    const TICK: Sym = Sym(1);
    #[derive(Clone, Copy)]
    enum Frame {
        Call,
        Stop,
        Odd,
        Read,
        Done(i64, Sym),
    }
    let mut stack: Vec<Frame> = vec![Frame::Call];
    let (mut pipe, mut n, mut t) = (limit, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Call => stack.push(Frame::Read),
            Frame::Stop | Frame::Odd => {
                t += 1;
                stack.pop();
            }
            Frame::Read => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Done(pipe, black_box(TICK));
            }
            Frame::Done(k, tag) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if tag == TICK {
                        n = black_box(n + 1);
                        if n >= k {
                            Frame::Stop
                        } else {
                            Frame::Call
                        }
                    } else {
                        Frame::Odd
                    };
                }
            }
        }
    }
    t
}

/// (d) `r19_d_global_goal` (helper `review19`): a walk comparing each spot
/// with a global read at each visit (`black_box` on the read: the global
/// may change between visits), set once by the first situation.
pub fn hand_r19_global_goal(rounds: i64, spots: &[Sym], goal: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Setup,
        Round,
        Stop,
        Begin,
        At(&'a [Sym]),
        Hit(Sym),
        Miss,
    }
    let mut global = Sym(u32::MAX);
    let mut stack: Vec<Frame> = vec![Frame::Setup];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Setup => {
                t += 1;
                global = black_box(goal);
                *top = Frame::Round;
            }
            Frame::Round => stack.push(Frame::Begin),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::At(spots);
            }
            Frame::At([]) => {
                t += 1;
                *top = Frame::Miss;
            }
            Frame::At([s, ss @ ..]) => {
                t += 1;
                *top = if *s == black_box(global) {
                    Frame::Hit(*s)
                } else {
                    Frame::At(ss)
                };
            }
            f @ (Frame::Hit(_) | Frame::Miss) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (c) `r19_c_ping_pong` (helper `review19`): two DMs calling each other,
/// `ping(D)` calls `pong(D)` while `D > 0`, `pong(D)` calls `ping(D - 1)`;
/// a frame a level on the explicit stack, each ending in `back`.
pub fn hand_r19_ping_pong(rounds: i64, depth: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Serve,
        Stop,
        PingLook(i64),
        PingHit(i64),
        PongLook(i64),
        PongHit(i64),
        Back,
    }
    let mut stack: Vec<Frame> = vec![Frame::Serve];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Serve => stack.push(Frame::PingLook(black_box(depth))),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::PingLook(d) => {
                t += 1;
                *top = if d > 0 {
                    Frame::PingHit(d)
                } else {
                    Frame::Back
                };
            }
            Frame::PingHit(d) => stack.push(Frame::PongLook(d)),
            Frame::PongLook(d) => {
                t += 1;
                *top = Frame::PongHit(d - 1);
            }
            Frame::PongHit(e) => stack.push(Frame::PingLook(e)),
            Frame::Back => {
                // The final, then the caller's recursive situation on `back`.
                t += 2;
                stack.pop();
                match stack.last_mut() {
                    Some(Frame::Serve) => {
                        n = black_box(n + 1);
                        if n >= rounds {
                            *stack.last_mut().unwrap() = Frame::Stop;
                        }
                    }
                    Some(f) => *f = Frame::Back,
                    None => unreachable!(),
                }
            }
        }
    }
    t
}

/// (d) `r19_d_chain3` (helper `review19`): `list_search` with three
/// situations an element (`box`, `label`, `skip`), one state each.
pub fn hand_r19_chain3(rounds: i64, boxes: &[Sym], label: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Open,
        Box(&'a [Sym]),
        Label(Sym, &'a [Sym]),
        Skip(&'a [Sym]),
        Match(Sym),
        NoMatch,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Open),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::Open => {
                t += 1;
                *top = Frame::Box(boxes);
            }
            Frame::Box([]) => {
                t += 1;
                *top = Frame::NoMatch;
            }
            Frame::Box([b, bs @ ..]) => {
                t += 1;
                *top = Frame::Label(*b, bs);
            }
            Frame::Label(b, bs) => {
                t += 1;
                *top = if b == label {
                    Frame::Match(b)
                } else {
                    Frame::Skip(bs)
                };
            }
            Frame::Skip(bs) => {
                t += 1;
                *top = Frame::Box(bs);
            }
            f @ (Frame::Match(_) | Frame::NoMatch) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (d) `r19_d_when_qty` (helper `review19`): `item(Name, Qty)` records,
/// the first with `Qty >= need` ends the walk (`when/3` in the DM).
pub fn hand_r19_when_qty(rounds: i64, items: &[Item], need: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        First,
        Bin(&'a [Item]),
        Enough(Sym),
        Short,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::First),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::First => {
                t += 1;
                *top = Frame::Bin(items);
            }
            Frame::Bin([]) => {
                t += 1;
                *top = Frame::Short;
            }
            Frame::Bin([Item(name, qty), is @ ..]) => {
                t += 1;
                *top = if *qty >= need {
                    Frame::Enough(*name)
                } else {
                    Frame::Bin(is)
                };
            }
            f @ (Frame::Enough(_) | Frame::Short) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}

/// (d) `r19_d_prolog_first` (helper `review19`): the first crate a
/// predicate accepts (the DM's Prolog `heavy/1`, here the comparison it
/// makes, behind a function pointer as a call would be).
pub fn hand_r19_prolog_first(rounds: i64, crates: &[i64], heavy: fn(i64) -> bool) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Round,
        Stop,
        Load,
        Crate(&'a [i64]),
        Heavy(i64),
        Light,
    }
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Load),
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
            Frame::Load => {
                t += 1;
                *top = Frame::Crate(crates);
            }
            Frame::Crate([]) => {
                t += 1;
                *top = Frame::Light;
            }
            Frame::Crate([w, ws @ ..]) => {
                t += 1;
                *top = if heavy(*w) {
                    Frame::Heavy(*w)
                } else {
                    Frame::Crate(ws)
                };
            }
            f @ (Frame::Heavy(_) | Frame::Light) => {
                t += 2;
                black_box(f);
                stack.pop();
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Stop
                    } else {
                        Frame::Round
                    };
                }
            }
        }
    }
    t
}
