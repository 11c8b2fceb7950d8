//! The hand-written Rust machine of helper `nfloat25`'s workload
//! (`tests/typed/nfloat25/n25_d_float_band`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand24.rs` is:
//! it does the workload's work (lists slices, frames an enum on an
//! explicit stack, the Prolog function behind a function pointer as a
//! call would be, `black_box` where the compiled task has an observable
//! effect) and returns its transitions, which must be the workload's.
#![allow(dead_code)]

use super::black_box;

/// (d) `n25_d_float_band`: the first float reading a predicate puts in
/// the band above the floor `lo` (the DM's Prolog `inband/3`), the
/// sweep's rest handed on; the rounds counted by the caller's id.
pub fn hand_n25_float_band(rounds: i64, xs: &[f64], lo: f64, inband: fn(f64, f64) -> bool) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Idle,
        Round(i64),
        Halt,
        Open,
        Scan(&'a [f64]),
        Hit(f64),
        Miss,
    }
    let mut stack: Vec<Frame> = vec![Frame::Idle];
    let mut t = 0u64;
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Idle => {
                t += 1;
                *top = Frame::Round(0);
            }
            Frame::Round(_) => stack.push(Frame::Open),
            Frame::Halt => {
                t += 1;
                stack.pop();
            }
            Frame::Open => {
                t += 1;
                *top = Frame::Scan(xs);
            }
            Frame::Scan([]) => {
                t += 1;
                *top = Frame::Miss;
            }
            Frame::Scan([x, rest @ ..]) => {
                t += 1;
                *top = if inband(*x, lo) {
                    Frame::Hit(*x)
                } else {
                    Frame::Scan(rest)
                };
            }
            f @ (Frame::Hit(_) | Frame::Miss) => {
                t += 2;
                black_box(f);
                stack.pop();
                if let Some(m @ Frame::Round(_)) = stack.last_mut() {
                    let Frame::Round(i) = *m else { unreachable!() };
                    let j = i + 1;
                    *m = if j >= rounds {
                        Frame::Halt
                    } else {
                        Frame::Round(j)
                    };
                }
            }
        }
    }
    t
}
