//! The hand-written Rust machines of helper `ngauge25`'s workloads
//! (`tests/typed/ngauge25`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: each
//! does its workload's work (lists slices, frames an enum on an explicit
//! stack, `black_box` where the compiled task has an observable effect: a
//! value handed back by the pipe or by a final's id) and returns its
//! transitions, which must be the workload's.
#![allow(dead_code)]

use super::black_box;

/// (c) `g25_c_float_prog`: `cycle(I)` calls `drain`, whose situation
/// takes the charge from the pipe, computes the next one (`L1 is L * 2.0
/// * 0.25 + 1.25`, a float) and hands it on; above 100.0 the final is
/// `flat`, else `ok`.
pub fn hand_g25_float_prog(rounds: i64, charge: f64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Start,
        Cycle(i64),
        Stop,
        Use,
        Ok,
        Flat,
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let (mut pipe, mut t) = (0.0f64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                pipe = black_box(charge);
                *top = Frame::Cycle(0);
            }
            Frame::Cycle(_) => stack.push(Frame::Use),
            Frame::Use => {
                t += 1;
                let l1 = pipe * 2.0 * 0.25 + 1.25;
                pipe = black_box(l1);
                *top = if l1 > 100.0 { Frame::Flat } else { Frame::Ok };
            }
            Frame::Ok | Frame::Flat => {
                t += 2;
                stack.pop();
                if let Some(m @ Frame::Cycle(_)) = stack.last_mut() {
                    let Frame::Cycle(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j < rounds {
                        Frame::Cycle(j)
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

/// (d) `g25_d_float_next`: `round(I)` calls `sum(Weights, Cap)`, which
/// walks the weights with the running load a float in the walk's id
/// (`add(Rest, _ is S + W * 0.5)`) until it passes the cap (`over(S)`) or
/// the weights end (`under(S)`).
pub fn hand_g25_float_next(rounds: i64, weights: &[i64], cap: f64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Start,
        Round(i64),
        Stop,
        Begin,
        Add(&'a [i64], f64),
        Over(f64),
        Under(f64),
    }
    let mut stack: Vec<Frame> = vec![Frame::Start];
    let mut t = 0u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Start => {
                t += 1;
                *top = Frame::Round(0);
            }
            Frame::Round(_) => stack.push(Frame::Begin),
            Frame::Begin => {
                t += 1;
                *top = Frame::Add(weights, 0.0);
            }
            Frame::Add([], s) => {
                t += 1;
                *top = Frame::Under(s);
            }
            Frame::Add([w, ws @ ..], s) => {
                t += 1;
                *top = if s > cap {
                    Frame::Over(s)
                } else {
                    Frame::Add(ws, s + *w as f64 * 0.5)
                };
            }
            Frame::Over(s) | Frame::Under(s) => {
                t += 2;
                black_box(s);
                stack.pop();
                if let Some(m @ Frame::Round(_)) = stack.last_mut() {
                    let Frame::Round(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j < rounds {
                        Frame::Round(j)
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
