//! The hand-written Rust machines of helper `review22`'s workloads
//! (`tests/typed/review22`, issue 37), included by
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

/// (c) `r22_c_stage_global`: `launch` calls `stage` while the global
/// count is under the budget (the pipe, handed back by the callee); the
/// callee ends `lit` for a positive pipe, else `dud`.
pub fn hand_r22_stage_global(budget: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Fire,
        Landed,
        Scrubbed,
        Ignite,
        Lit,
        Dud,
    }
    let mut stack: Vec<Frame> = vec![Frame::Fire];
    let (mut pipe, mut fired, mut t) = (budget, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Fire => stack.push(Frame::Ignite),
            Frame::Landed | Frame::Scrubbed => {
                t += 1;
                stack.pop();
            }
            Frame::Ignite => {
                t += 1;
                pipe = black_box(pipe);
                *top = if pipe > 0 { Frame::Lit } else { Frame::Dud };
            }
            f @ (Frame::Lit | Frame::Dud) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if matches!(f, Frame::Lit) {
                        fired = black_box(fired + 1);
                        if fired >= pipe {
                            Frame::Landed
                        } else {
                            Frame::Fire
                        }
                    } else {
                        Frame::Scrubbed
                    };
                }
            }
        }
    }
    t
}

/// (c) `r22_c_ferry_two`: `depart` calls `ferry(Trips)`, which hands the
/// pipe back and ends `docked(L)`; `tally(T)` counts in a local and goes
/// back to `depart` while under `T`.
pub fn hand_r22_ferry_two(trips: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Depart,
        Tally(i64),
        Moored,
        Sail,
        Docked(i64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Depart];
    let (mut pipe, mut done, mut t) = (trips, 0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Depart => stack.push(Frame::Sail),
            Frame::Sail => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Docked(pipe);
            }
            Frame::Docked(l) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Tally(l);
                }
            }
            Frame::Tally(limit) => {
                t += 1;
                done = black_box(done + 1);
                *top = if done < limit {
                    Frame::Depart
                } else {
                    Frame::Moored
                };
            }
            Frame::Moored => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r22_c_lap_pipe`: the pipe a pair `(count, limit)`; the callee adds
/// one and ends `finished` at the limit, else `going`.
pub fn hand_r22_lap_pipe(laps: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Run,
        Podium,
        Stride,
        Going,
        Finished,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut t) = ((0i64, 0i64), 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                pipe = black_box((0, laps));
                *top = Frame::Run;
            }
            Frame::Run => stack.push(Frame::Stride),
            Frame::Stride => {
                t += 1;
                let (k, m) = pipe;
                let k1 = k + 1;
                pipe = black_box((k1, m));
                *top = if k1 >= m {
                    Frame::Finished
                } else {
                    Frame::Going
                };
            }
            f @ (Frame::Going | Frame::Finished) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if matches!(f, Frame::Going) {
                        Frame::Run
                    } else {
                        Frame::Podium
                    };
                }
            }
            Frame::Podium => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (c) `r22_c_rung_id`: the count in the recursive situation's id,
/// `rung(I)`, the limit the pipe the callee hands back.
pub fn hand_r22_rung_id(top_rung: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Base,
        Rung(i64),
        Roof,
        Step,
        Up,
    }
    let mut stack: Vec<Frame> = vec![Frame::Base];
    let (mut pipe, mut t) = (top_rung, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Base => {
                t += 1;
                *top = Frame::Rung(black_box(1));
            }
            Frame::Rung(_) => stack.push(Frame::Step),
            Frame::Step => {
                t += 1;
                pipe = black_box(pipe);
                *top = Frame::Up;
            }
            Frame::Up => {
                t += 2;
                stack.pop();
                if let Some(m @ Frame::Rung(_)) = stack.last_mut() {
                    let Frame::Rung(i) = *m else { unreachable!() };
                    *m = if i >= pipe {
                        Frame::Roof
                    } else {
                        Frame::Rung(i + 1)
                    };
                }
            }
            Frame::Roof => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// (d) `r22_d_sweep_say`: the walk saying each room it checks (the line
/// test mode writes, `Golem says: checking p3`, formatted into a sink as
/// the effector does), the rounds counted in a local.
pub fn hand_r22_sweep_say(rounds: i64, rooms: &[Sym], names: &[String], lost: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Go,
        Home,
        Enter,
        Try(&'a [Sym]),
        Found(Sym),
        NotFound,
        Nothing,
    }
    let mut out = std::io::sink();
    let mut stack: Vec<Frame> = vec![Frame::Go];
    let (mut laps, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Go => stack.push(Frame::Enter),
            Frame::Home => {
                t += 1;
                stack.pop();
            }
            Frame::Enter => {
                t += 1;
                *top = if rooms.is_empty() {
                    Frame::Nothing
                } else {
                    Frame::Try(rooms)
                };
            }
            Frame::Try([]) => {
                t += 1;
                let line = "Golem says: not here".to_owned();
                let _ = writeln!(black_box(&mut out), "{line}");
                *top = Frame::NotFound;
            }
            Frame::Try([r, rs @ ..]) => {
                t += 1;
                let line = format!("Golem says: checking {}", names[r.0 as usize]);
                let _ = writeln!(black_box(&mut out), "{line}");
                *top = if *r == lost {
                    Frame::Found(*r)
                } else {
                    Frame::Try(rs)
                };
            }
            f @ (Frame::Found(_) | Frame::NotFound | Frame::Nothing) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = if matches!(f, Frame::Nothing) {
                        Frame::Home
                    } else {
                        laps = black_box(laps + 1);
                        if laps >= rounds {
                            Frame::Home
                        } else {
                            Frame::Go
                        }
                    };
                }
            }
        }
    }
    t
}

/// (d) `r22_d_stock_expect`: pairs `(name, qty)`, each handed to a callee
/// (a frame of its own) that ends with the pair's key, which the walker's
/// exit arcs compare with the wanted name.
pub fn hand_r22_stock_expect(rounds: i64, stock: &[(Sym, i64)], want: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Ask,
        Closed,
        Begin,
        Try(&'a [(Sym, i64)]),
        Found((Sym, i64)),
        NotFound,
        Split((Sym, i64)),
        Key(Sym),
    }
    let mut stack: Vec<Frame> = vec![Frame::Ask];
    let (mut asked, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Ask => stack.push(Frame::Begin),
            Frame::Closed => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Try(stock);
            }
            Frame::Try([]) => {
                t += 1;
                *top = Frame::NotFound;
            }
            Frame::Try([p, ..]) => stack.push(Frame::Split(*p)),
            Frame::Split((k, _)) => {
                t += 1;
                *top = Frame::Key(k);
            }
            Frame::Key(k) => {
                t += 2;
                stack.pop();
                if let Some(m @ Frame::Try([_, ..])) = stack.last_mut() {
                    let Frame::Try([p, ps @ ..]) = *m else {
                        unreachable!()
                    };
                    *m = if k == want {
                        Frame::Found(*p)
                    } else {
                        Frame::Try(ps)
                    };
                }
            }
            f @ (Frame::Found(_) | Frame::NotFound) => {
                t += 2;
                black_box(f);
                stack.pop();
                asked = black_box(asked + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if asked >= rounds {
                        Frame::Closed
                    } else {
                        Frame::Ask
                    };
                }
            }
        }
    }
    t
}

/// (d) `r22_d_floor_fn`: the first reading a predicate accepts against a
/// floor (the DM's Prolog `reaches/2`, here its comparison behind a
/// function pointer as a call would be); the rounds counted in a global.
pub fn hand_r22_floor_fn(
    rounds: i64,
    readings: &[i64],
    floor: i64,
    reaches: fn(i64, i64) -> bool,
) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Poll,
        Off,
        Begin,
        Try(&'a [i64]),
        Found(i64),
        NotFound,
    }
    let mut stack: Vec<Frame> = vec![Frame::Poll];
    let (mut polls, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Poll => stack.push(Frame::Begin),
            Frame::Off => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Try(readings);
            }
            Frame::Try([]) => {
                t += 1;
                *top = Frame::NotFound;
            }
            Frame::Try([v, vs @ ..]) => {
                t += 1;
                *top = if reaches(*v, floor) {
                    Frame::Found(*v)
                } else {
                    Frame::Try(vs)
                };
            }
            f @ (Frame::Found(_) | Frame::NotFound) => {
                t += 2;
                black_box(f);
                stack.pop();
                polls = black_box(polls + 1);
                if let Some(m) = stack.last_mut() {
                    *m = if polls >= rounds {
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

/// (d) `r22_d_goal_local`: the target set in a local at the walk's start
/// and read back at each look (`black_box` on the read), two situations
/// an element; the rounds left in the pipe, one taken off by `tick`.
pub fn hand_r22_goal_local(rounds: i64, spots: &[Sym], goal: Sym) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Start,
        Call,
        Tick,
        Stop,
        Begin,
        Try(&'a [Sym]),
        Look(Sym, &'a [Sym]),
        Found(Sym),
        NotFound,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut local, mut t) = (0i64, Sym(u32::MAX), 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                pipe = black_box(rounds);
                *top = Frame::Call;
            }
            Frame::Call => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                local = black_box(goal);
                *top = Frame::Try(spots);
            }
            Frame::Try([]) => {
                t += 1;
                *top = Frame::NotFound;
            }
            Frame::Try([s, ss @ ..]) => {
                t += 1;
                *top = Frame::Look(*s, ss);
            }
            Frame::Look(s, ss) => {
                t += 1;
                *top = if s == black_box(local) {
                    Frame::Found(s)
                } else {
                    Frame::Try(ss)
                };
            }
            f @ (Frame::Found(_) | Frame::NotFound) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Tick;
                }
            }
            Frame::Tick => {
                t += 1;
                pipe = black_box(pipe - 1);
                *top = if pipe > 0 { Frame::Call } else { Frame::Stop };
            }
            Frame::Stop => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}

/// Helper `nglob24`'s `g24_d_grow_list` (issue 37): `budget` steps, each
/// reading the global list (`get(seen, S)`), counting (`inc(count, C)`) and
/// setting the list one element longer (`set(seen, [C|S])`), the values
/// performed (`black_box`: the effector ignores a list and a number); then
/// `check` (the list not empty) and `done`. The list a persistent cons list
/// (`Rc` cells): a read and a write take constant time.
pub fn hand_g24_grow_list(budget: i64) -> u64 {
    use std::rc::Rc;
    struct Cell(i64, Option<Rc<Cell>>);
    let (mut seen, mut count, mut t): (Option<Rc<Cell>>, i64, u64) = (None, 0, 0);
    loop {
        t += 1;
        let s = black_box(seen.clone());
        count = black_box(count + 1);
        seen = Some(Rc::new(Cell(count, s)));
        black_box(&seen);
        if count >= black_box(budget) {
            break;
        }
    }
    // `check`, then the final `done` (the list is not empty).
    t += 1;
    black_box(seen.as_ref().map(|c| c.0));
    t + 1
}
