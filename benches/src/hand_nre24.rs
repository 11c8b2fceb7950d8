//! The hand-written Rust machines of helper `nre24`'s workloads
//! (`tests/typed/nre24`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: each
//! does its workload's work (atoms an interned index, lists slices, frames
//! an enum on an explicit stack, `black_box` where the compiled task has an
//! observable effect) and returns its transitions, which must be the
//! workload's.
#![allow(dead_code)]

use super::black_box;
use super::hand::Sym;

/// (d) `n24_d_note_walk`: a walk whose every place calls a callee (a frame
/// of its own) that ends with the place, the exit arc's action a user
/// function (`note/1`, here a function pointer as a call would be), then
/// a situation that compares the place with the wanted one.
pub fn hand_n24_note_walk(rounds: i64, places: &[Sym], want: Sym, note: fn(Sym)) -> u64 {
    #[derive(Clone, Copy)]
    enum Frame<'a> {
        Ask,
        Closed,
        Begin,
        Visit(&'a [Sym]),
        Check(Sym, &'a [Sym]),
        Found(Sym),
        NotFound,
        Look(Sym),
        Seen(Sym),
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
                *top = Frame::Visit(places);
            }
            Frame::Visit([]) => {
                t += 1;
                *top = Frame::NotFound;
            }
            Frame::Visit([p, ..]) => stack.push(Frame::Look(*p)),
            Frame::Look(p) => {
                t += 1;
                *top = Frame::Seen(p);
            }
            Frame::Seen(s) => {
                t += 2;
                stack.pop();
                note(s);
                if let Some(m @ Frame::Visit([_, ..])) = stack.last_mut() {
                    let Frame::Visit([_, ps @ ..]) = *m else {
                        unreachable!()
                    };
                    *m = Frame::Check(s, ps);
                }
            }
            Frame::Check(s, ps) => {
                t += 1;
                *top = if s == want {
                    Frame::Found(s)
                } else {
                    Frame::Visit(ps)
                };
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
