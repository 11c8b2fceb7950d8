//! The hand-written Rust machines of helper `review24`'s workloads
//! (`tests/typed/review24`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: each
//! does its workload's work (atoms an interned index, lists slices, frames
//! an enum on an explicit stack, `black_box` where the compiled task has an
//! observable effect: a global or local written, a value handed back by the
//! pipe, a sentence said) and returns its transitions, which must be the
//! workload's.
#![allow(dead_code)]

use super::black_box;
use super::hand::Sym;
use std::io::Write;

/// (c) `r24_c_winch_param`: `pull` calls `spool(Got)`, which hands the
/// pipe back and binds `Got` to it through its parameter; the count a
/// local compared with `Got`.
pub fn hand_r24_winch_param(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Pull,
        Stowed,
        Reel,
        Wound(i64),
        Jammed,
    }
    let mut stack: Vec<Frame> = vec![Frame::Pull];
    let (mut pipe, mut turns, mut t) = (limit, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Pull => stack.push(Frame::Reel),
            Frame::Reel => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Wound(pipe);
            }
            Frame::Wound(got) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    turns = black_box(turns + 1);
                    *m = if turns >= got {
                        Frame::Stowed
                    } else {
                        Frame::Pull
                    };
                }
            }
            Frame::Jammed => {
                t += 2;
                stack.pop();
                let _ = writeln!(black_box(&mut std::io::sink()), "Golem says: jammed");
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Stowed;
                }
            }
            Frame::Stowed => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r24_c_mill_nested`: `mill(K)` (a float count) calls `grind`,
/// which calls `blade`; `blade` hands the pipe back, `grind` ends `kept`
/// for a positive pipe, else `worn`.
pub fn hand_r24_mill_nested(budget: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Open,
        Mill(f64),
        Idle,
        Turn,
        Kept,
        Worn,
        Hone,
        Sharp,
    }
    let mut stack: Vec<Frame> = vec![Frame::Open];
    let (mut pipe, mut t) = (budget, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Open => {
                t += 1;
                *top = Frame::Mill(black_box(0.0));
            }
            Frame::Mill(_) => stack.push(Frame::Turn),
            Frame::Turn => stack.push(Frame::Hone),
            Frame::Hone => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Sharp;
            }
            Frame::Sharp => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if pipe > 0 { Frame::Kept } else { Frame::Worn };
                }
            }
            f @ (Frame::Kept | Frame::Worn) => {
                t += 2;
                stack.pop();
                if let Some(m @ Frame::Mill(_)) = stack.last_mut() {
                    let Frame::Mill(k) = *m else { unreachable!() };
                    *m = match f {
                        Frame::Kept => {
                            let k1 = k + 1.0;
                            if k1 >= pipe as f64 {
                                Frame::Idle
                            } else {
                                Frame::Mill(k1)
                            }
                        }
                        _ => Frame::Idle,
                    };
                }
            }
            Frame::Idle => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r24_d_gauge_guard`: the first reading above the cap (a global
/// written once a run), a negative one an error; the rounds left the pipe,
/// one taken off by the caller's exit arc.
pub fn hand_r24_gauge_guard(rounds: i64, readings: &[i64], cap: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Start,
        Watch,
        Rest,
        Begin,
        Try(&'a [i64]),
        Found(i64),
        NotFound,
        Error(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut global_cap, mut t) = (0i64, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                global_cap = black_box(cap);
                pipe = black_box(rounds);
                *top = Frame::Watch;
            }
            Frame::Watch => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                *top = Frame::Try(readings);
            }
            Frame::Try([]) => {
                t += 1;
                *top = Frame::NotFound;
            }
            Frame::Try([x, xs @ ..]) => {
                t += 1;
                *top = if *x < 0 {
                    Frame::Error(*x)
                } else if *x > global_cap {
                    Frame::Found(*x)
                } else {
                    Frame::Try(xs)
                };
            }
            f @ (Frame::Found(_) | Frame::NotFound) => {
                t += 2;
                black_box(f);
                stack.pop();
                pipe = black_box(pipe - 1);
                if let Some(m) = stack.last_mut() {
                    *m = if pipe > 0 { Frame::Watch } else { Frame::Rest };
                }
            }
            Frame::Error(e) => {
                t += 2;
                stack.pop();
                let _ = writeln!(
                    black_box(&mut std::io::sink()),
                    "Golem says: bad reading negative({e})"
                );
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Rest;
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

/// (d) `r24_d_where_pairs`: pairs `(name, place)` searched by the name;
/// the place of the one found said once a round by the caller (the line
/// test mode writes, formatted into a sink as the effector does), the
/// rounds counted in a local.
pub fn hand_r24_where_pairs(
    rounds: i64,
    people: &[(Sym, Sym)],
    who: Sym,
    names: &[String],
    places: &[String],
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Ask,
        Done,
        Begin,
        Look(&'a [(Sym, Sym)]),
        At(Sym),
        Nowhere,
    }
    let mut out = std::io::sink();
    let mut stack: Vec<Frame> = vec![Frame::Ask];
    let (mut asked, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Ask => stack.push(Frame::Begin),
            Frame::Done => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Look(people);
            }
            Frame::Look([]) => {
                t += 1;
                *top = Frame::Nowhere;
            }
            Frame::Look([(n, p), rest @ ..]) => {
                t += 1;
                *top = if *n == who {
                    Frame::At(*p)
                } else {
                    Frame::Look(rest)
                };
            }
            f @ (Frame::At(_) | Frame::Nowhere) => {
                t += 2;
                stack.pop();
                if let Frame::At(p) = f {
                    let line = format!(
                        "Golem says: found {} at {}",
                        names[who.0 as usize], places[p.0 as usize]
                    );
                    let _ = writeln!(black_box(&mut out), "{line}");
                }
                asked = black_box(asked + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if asked >= rounds {
                        Frame::Done
                    } else {
                        Frame::Ask
                    };
                }
            }
        }
    }
    t
}

/// (d) `r24_d_sift_two_lists`: the walker's id holds the items to go and
/// those passed (a list grown by one a step, kept in a vector cleared a
/// round); each item compared by a callee frame of its own.
pub fn hand_r24_sift_two_lists(rounds: i64, items: &[Sym], want: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Open,
        Pass(i64),
        Tidy,
        Begin,
        Step(&'a [Sym]),
        Hit(Sym),
        Miss,
        Cmp(Sym, Sym),
        Yes,
        No,
    }
    let mut stack: Vec<Frame> = vec![Frame::Open];
    let mut passed: Vec<Sym> = Vec::with_capacity(items.len());
    let mut t = 0u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Open => {
                t += 1;
                *top = Frame::Pass(0);
            }
            Frame::Pass(_) => stack.push(Frame::Begin),
            Frame::Tidy => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                passed.clear();
                *top = Frame::Step(items);
            }
            Frame::Step([]) => {
                t += 1;
                *top = Frame::Miss;
            }
            Frame::Step([i, ..]) => stack.push(Frame::Cmp(*i, want)),
            Frame::Cmp(a, b) => {
                t += 1;
                *top = if a == b { Frame::Yes } else { Frame::No };
            }
            f @ (Frame::Yes | Frame::No) => {
                t += 2;
                stack.pop();
                if let Some(m @ Frame::Step([_, ..])) = stack.last_mut() {
                    let Frame::Step([i, is @ ..]) = *m else {
                        unreachable!()
                    };
                    *m = if matches!(f, Frame::Yes) {
                        Frame::Hit(*i)
                    } else {
                        passed.push(*i);
                        Frame::Step(is)
                    };
                }
            }
            f @ (Frame::Hit(_) | Frame::Miss) => {
                t += 2;
                black_box((f, &passed));
                stack.pop();
                if let Some(m @ Frame::Pass(_)) = stack.last_mut() {
                    let Frame::Pass(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j >= rounds {
                        Frame::Tidy
                    } else {
                        Frame::Pass(j)
                    };
                }
            }
        }
    }
    t
}

/// (d) `r24_d_near_floats`: the first float a predicate finds near the
/// target (the DM's Prolog `near/2`, here behind a function pointer as a
/// call would be), the target read into a local once a round; the rounds
/// counted by the caller's id.
pub fn hand_r24_near_floats(
    rounds: i64,
    freqs: &[f64],
    target: f64,
    near: fn(f64, f64) -> bool,
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Power,
        Scan(i64),
        Off,
        Begin,
        Next(&'a [f64]),
        Locked(f64),
        Static,
    }
    let mut stack: Vec<Frame> = vec![Frame::Power];
    let (mut want, mut t) = (0.0f64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Power => {
                t += 1;
                *top = Frame::Scan(0);
            }
            Frame::Scan(_) => stack.push(Frame::Begin),
            Frame::Off => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                want = black_box(target);
                *top = Frame::Next(freqs);
            }
            Frame::Next([]) => {
                t += 1;
                *top = Frame::Static;
            }
            Frame::Next([f, fs @ ..]) => {
                t += 1;
                *top = if near(*f, want) {
                    Frame::Locked(*f)
                } else {
                    Frame::Next(fs)
                };
            }
            f @ (Frame::Locked(_) | Frame::Static) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m @ Frame::Scan(_)) = stack.last_mut() {
                    let Frame::Scan(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j >= rounds {
                        Frame::Off
                    } else {
                        Frame::Scan(j)
                    };
                }
            }
        }
    }
    t
}
