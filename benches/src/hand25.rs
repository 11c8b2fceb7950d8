//! The hand-written Rust machines of helper `review25`'s workloads
//! (`tests/typed/review25`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: each
//! does its workload's work (atoms an interned index, lists slices, frames
//! an enum on an explicit stack, `black_box` where the compiled task has an
//! observable effect: a local written, a value handed back by the pipe, a
//! list built) and returns its transitions, which must be the workload's.
#![allow(dead_code)]

use super::black_box;
use super::hand::Sym;

/// (c) `r25_c_pass_limit`: the count the pipe, the limit a parameter
/// passed on to `hop` and on to `edge`; `edge` hands the pipe back and ends
/// `below` or `reached`, the caller adds one after the call.
pub fn hand_r25_pass_limit(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Go,
        Stop,
        Via(i64),
        Peek(i64),
        Below,
        Reached,
        More,
        Enough,
    }
    let mut stack: Vec<Frame> = vec![Frame::Go];
    let (mut pipe, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Go => stack.push(Frame::Via(limit)),
            Frame::Via(l) => stack.push(Frame::Peek(l)),
            Frame::Peek(l) => {
                t += 1;
                pipe = black_box(pipe);
                *top = if pipe < l {
                    Frame::Below
                } else {
                    Frame::Reached
                };
            }
            f @ (Frame::Below | Frame::Reached) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if matches!(f, Frame::Below) {
                        Frame::More
                    } else {
                        Frame::Enough
                    };
                }
            }
            f @ (Frame::More | Frame::Enough) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if matches!(f, Frame::More) {
                        pipe = black_box(pipe + 1);
                        Frame::Go
                    } else {
                        Frame::Stop
                    };
                }
            }
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r25_c_rota_list`: one shift to each of the crew in turn (the
/// rest of the crew a slice in the frame, refilled when empty), the count
/// the pipe; `cy` rests, the others work.
pub fn hand_r25_rota_list(limit: i64, crew: &[Sym], cy: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Spin(&'a [Sym]),
        Off,
        Clock(Sym),
        Worked,
        Rested,
    }
    let mut stack: Vec<Frame> = vec![Frame::Spin(&[])];
    let (mut pipe, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Spin([]) => {
                t += 1;
                *top = Frame::Spin(crew);
            }
            Frame::Spin([w, ..]) => stack.push(Frame::Clock(*w)),
            Frame::Clock(w) => {
                t += 1;
                pipe = black_box(pipe);
                *top = if w == cy {
                    Frame::Rested
                } else {
                    Frame::Worked
                };
            }
            f @ (Frame::Worked | Frame::Rested) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m @ Frame::Spin([_, ..])) = stack.last_mut() {
                    let Frame::Spin([_, ws @ ..]) = *m else {
                        unreachable!()
                    };
                    pipe = black_box(pipe + 1);
                    *m = if pipe >= limit {
                        Frame::Off
                    } else {
                        Frame::Spin(ws)
                    };
                }
            }
            Frame::Off => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// An `obj(Name, Place, Weight)` record of `r25_d_obj_records`.
#[derive(Clone, Copy)]
pub struct Obj(pub Sym, pub Sym, pub i64);

/// (d) `r25_d_obj_records`: the first record in the kitchen heavier than
/// `max`; the rounds left a local read and written once a round.
pub fn hand_r25_obj_records(rounds: i64, objs: &[Obj], max: i64, kitchen: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Start,
        Trip,
        Rest,
        Begin,
        Look(&'a [Obj]),
        Lift(Sym),
        Nothing,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut left, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                left = black_box(rounds);
                *top = Frame::Trip;
            }
            Frame::Trip => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                *top = Frame::Look(objs);
            }
            Frame::Look([]) => {
                t += 1;
                *top = Frame::Nothing;
            }
            Frame::Look([Obj(n, p, w), os @ ..]) => {
                t += 1;
                *top = if *p != kitchen {
                    Frame::Look(os)
                } else if *w > max {
                    Frame::Lift(*n)
                } else {
                    Frame::Look(os)
                };
            }
            f @ (Frame::Lift(_) | Frame::Nothing) => {
                t += 2;
                black_box(f);
                stack.pop();
                left = black_box(left - 1);
                if let Some(m) = stack.last_mut() {
                    *m = if left <= 0 { Frame::Rest } else { Frame::Trip };
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

/// (d) `r25_d_prolog_route`: the stops without `hall` (filtered once, as
/// the Prolog function is asked once), walked each round for the target;
/// a place found is `kitchen` (a second local counted) or another.
pub fn hand_r25_prolog_route(
    rounds: i64,
    stops: &[Sym],
    target: Sym,
    hall: Sym,
    kitchen: Sym,
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Plan,
        Round,
        Home,
        Begin,
        Stop(&'a [Sym]),
        At(Sym),
        Lost,
    }
    // The function's answer, asked once a run (at `Plan`).
    let route: Vec<Sym> = stops.iter().copied().filter(|&s| s != hall).collect();
    let mut stack: Vec<Frame> = vec![Frame::Plan];
    let (mut n, mut cooks, mut t) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Plan => {
                t += 1;
                black_box(&route);
                *top = Frame::Round;
            }
            Frame::Round => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                *top = Frame::Stop(&route);
            }
            Frame::Stop([]) => {
                t += 1;
                *top = Frame::Lost;
            }
            Frame::Stop([p, ps @ ..]) => {
                t += 1;
                *top = if *p == target {
                    Frame::At(*p)
                } else {
                    Frame::Stop(ps)
                };
            }
            f @ (Frame::At(_) | Frame::Lost) => {
                t += 2;
                stack.pop();
                if let Frame::At(p) = f {
                    if p == kitchen {
                        cooks = black_box(cooks + 1);
                    }
                }
                n = black_box(n + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if n >= rounds {
                        Frame::Home
                    } else {
                        Frame::Round
                    };
                }
            }
            Frame::Home => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r25_d_filter_out`: each round the stops that are not `drop`
/// collected into a list (a vector cleared a round), handed back and read
/// by the caller.
pub fn hand_r25_filter_out(rounds: i64, stops: &[Sym], drop: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Load,
        Sort,
        Check,
        Done,
        Begin,
        Walk(&'a [Sym]),
        Kept,
    }
    let mut acc: Vec<Sym> = Vec::with_capacity(stops.len());
    let mut stack: Vec<Frame> = vec![Frame::Load];
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Load => {
                t += 1;
                *top = Frame::Sort;
            }
            Frame::Sort => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                acc.clear();
                *top = Frame::Walk(stops);
            }
            Frame::Walk([]) => {
                t += 1;
                black_box(&acc);
                *top = Frame::Kept;
            }
            Frame::Walk([p, ps @ ..]) => {
                t += 1;
                if *p != drop {
                    acc.push(*p);
                }
                *top = Frame::Walk(ps);
            }
            Frame::Kept => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Check;
                }
            }
            Frame::Check => {
                t += 1;
                n = black_box(n + 1);
                *top = if n >= rounds {
                    black_box(&acc);
                    Frame::Done
                } else {
                    Frame::Sort
                };
            }
            Frame::Done => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r25_d_strings`: strings (byte slices) compared whole with the one
/// wanted; the rounds counted in the caller's frame.
pub fn hand_r25_strings(rounds: i64, goods: &[Vec<u8>], want: &[u8]) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Enter,
        Aisle(i64),
        Till,
        Begin,
        Scan(&'a [Vec<u8>]),
        Got(&'a [u8]),
        None,
    }
    let mut stack: Vec<Frame> = vec![Frame::Enter];
    let mut t = 0u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Enter => {
                t += 1;
                *top = Frame::Aisle(0);
            }
            Frame::Aisle(_) => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                *top = Frame::Scan(goods);
            }
            Frame::Scan([]) => {
                t += 1;
                *top = Frame::None;
            }
            Frame::Scan([g, gs @ ..]) => {
                t += 1;
                *top = if g.as_slice() == want {
                    Frame::Got(g)
                } else {
                    Frame::Scan(gs)
                };
            }
            f @ (Frame::Got(_) | Frame::None) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m @ Frame::Aisle(_)) = stack.last_mut() {
                    let Frame::Aisle(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j >= rounds {
                        Frame::Till
                    } else {
                        Frame::Aisle(j)
                    };
                }
            }
            Frame::Till => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r25_d_mutual_walk`: one frame a place (the two DMs alike), the
/// answer handed back up through every frame.
pub fn hand_r25_mutual_walk(rounds: i64, places: &[Sym], target: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Out,
        Back,
        Step(&'a [Sym]),
        At(&'a [Sym]),
        On,
        Found(Sym),
        Missing,
    }
    let mut stack: Vec<Frame> = Vec::with_capacity(places.len() + 2);
    stack.push(Frame::Out);
    let (mut n, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Out => stack.push(Frame::Step(places)),
            Frame::Step(l) => {
                t += 1;
                *top = Frame::At(l);
            }
            Frame::At([]) => {
                t += 1;
                *top = Frame::Missing;
            }
            Frame::At([p, ps @ ..]) => {
                t += 1;
                if *p == target {
                    *top = Frame::Found(*p);
                } else {
                    *top = Frame::On;
                    stack.push(Frame::Step(ps));
                }
            }
            Frame::On => unreachable!("an `on` frame waits below its callee"),
            f @ (Frame::Found(_) | Frame::Missing) => {
                t += 2;
                stack.pop();
                match stack.last_mut() {
                    Some(m @ Frame::On) => *m = f,
                    Some(m) => {
                        black_box(f);
                        n = black_box(n + 1);
                        *m = if n >= rounds { Frame::Back } else { Frame::Out };
                    }
                    None => {}
                }
            }
            Frame::Back => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}
