//! The hand-written Rust machine of helper `nwinch25`'s workload
//! (`tests/typed/nwinch25/n25_c_tally_grade`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: it
//! does the workload's work (frames an enum on an explicit stack, the
//! pipe's kind decided by a `match` on its value, `black_box` where the
//! compiled task has an observable effect: the local written, the value
//! handed back through the parameter) and returns its transitions, which
//! must be the workload's.
#![allow(dead_code)]

use super::black_box;
use std::io::Write;

/// The pipe's value: the compiled task holds any ground value there.
#[derive(Clone, Copy)]
pub enum Pipe {
    Int(i64),
    Float(f64),
    Other,
}

/// (c) `n25_c_tally_grade`: `round` calls `grade(Cap)`, which decides the
/// pipe's kind (`integer(X), X > 0`, `float(X)`) and hands the pipe back
/// through `Cap` from `whole` or `frac` (`other` leaves it); the count a
/// local compared with `Cap`.
pub fn hand_n25_tally_grade(limit: i64) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame {
        Round,
        Done,
        Look,
        Whole(Pipe),
        Frac(Pipe),
        Other,
    }
    let pipe = Pipe::Int(limit);
    let mut stack: Vec<Frame> = vec![Frame::Round];
    let (mut count, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match *top {
            Frame::Round => stack.push(Frame::Look),
            Frame::Look => {
                t += 1;
                *top = match black_box(pipe) {
                    Pipe::Int(x) if x > 0 => Frame::Whole(pipe),
                    Pipe::Float(_) => Frame::Frac(pipe),
                    _ => Frame::Other,
                };
            }
            Frame::Whole(cap) | Frame::Frac(cap) => {
                t += 2;
                stack.pop();
                if let Some(m) = stack.last_mut() {
                    count = black_box(count + 1);
                    let over = match black_box(cap) {
                        Pipe::Int(c) => count >= c,
                        Pipe::Float(c) => count as f64 >= c,
                        Pipe::Other => true,
                    };
                    *m = if over { Frame::Done } else { Frame::Round };
                }
            }
            Frame::Other => {
                t += 2;
                stack.pop();
                let _ = writeln!(black_box(&mut std::io::sink()), "Golem says: not_a_number");
                if let Some(m) = stack.last_mut() {
                    *m = Frame::Done;
                }
            }
            Frame::Done => {
                t += 1;
                stack.pop();
            }
        }
    }
    t
}
