//! The hand-written Rust machine of helper `nmemo25`'s workload
//! (`tests/typed/nmemo25`, issue 37), included by
//! `benches/examples/shapes_prof.rs` with `#[path]` as `hand.rs` is: it
//! does its workload's work (atoms an interned index, the places a slice,
//! what was seen so far a persistent `Rc` list, frames an enum on an
//! explicit stack, `black_box` where the compiled task has an observable
//! effect) and returns its transitions, which must be the workload's.
#![allow(dead_code)]

use super::black_box;
use super::hand::Sym;
use std::rc::Rc;

/// A persistent list of places (`[S|Seen]` one cell, the tail shared).
struct Seen(Sym, Option<Rc<Seen>>);

/// (d) `n25_d_tally_walk`: `n24_d_note_walk`'s walk with what was seen so
/// far built at each place (`check(S, Ps, [S|Seen])`) and handed to the
/// final (`found(Seen)`, `not_found(Seen)`).
pub fn hand_n25_tally_walk(rounds: i64, places: &[Sym], want: Sym, note: fn(Sym)) -> u64 {
    type L = Option<Rc<Seen>>;
    enum Frame<'a> {
        Ask,
        Closed,
        Begin,
        Visit(&'a [Sym], L),
        Check(Sym, &'a [Sym], L),
        Found(L),
        NotFound(L),
        Look(Sym),
        Seen(Sym),
    }
    let mut stack: Vec<Frame> = vec![Frame::Ask];
    let (mut asked, mut t) = (0i64, 0u64);
    while let Some(top) = stack.last_mut() {
        match top {
            Frame::Ask => stack.push(Frame::Begin),
            Frame::Closed => {
                t += 1;
                stack.pop();
            }
            Frame::Begin => {
                t += 1;
                *top = Frame::Visit(places, None);
            }
            Frame::Visit([], seen) => {
                t += 1;
                *top = Frame::NotFound(seen.take());
            }
            Frame::Visit([p, ..], _) => {
                let p = *p;
                stack.push(Frame::Look(p));
            }
            Frame::Look(p) => {
                t += 1;
                *top = Frame::Seen(*p);
            }
            Frame::Seen(s) => {
                let s = *s;
                t += 2;
                stack.pop();
                note(s);
                if let Some(m) = stack.last_mut() {
                    if let Frame::Visit([_, ps @ ..], seen) = m {
                        let seen = Some(Rc::new(Seen(s, seen.take())));
                        *m = Frame::Check(s, ps, seen);
                    }
                }
            }
            Frame::Check(s, ps, seen) => {
                t += 1;
                let seen = seen.take();
                *top = if *s == want {
                    Frame::Found(seen)
                } else {
                    Frame::Visit(ps, seen)
                };
            }
            Frame::Found(seen) | Frame::NotFound(seen) => {
                t += 2;
                black_box(seen.as_ref().map(|c| c.0));
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
