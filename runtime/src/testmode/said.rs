//! Test mode's line of a `say` pattern planned once (issue 37: a `say` at
//! every step of a walk, `r22_d_sweep_say`).
//!
//! What it owns: [`Plans`], the lines `TextActions::perform_filled` writes
//! for a `say(M)` pattern (a program's constant, `Cx::fill`'s, marked as
//! it was read), each made once of the rule's text between its holes: the
//! constant items written, the separators the rule puts between them, and
//! the places where a hole's value goes. Writing the line is then the
//! pieces appended in order, each hole written as `write/1` writes it
//! alone (`sentence::write_seen`).
//!
//! Planned: `say(M)` with `M` a hole, or a proper list (its tail `[]`,
//! no hole as a tail) whose items are holes or hold none. Anything else
//! (a hole below a compound item, where an operator or a sign may change
//! the text around the value) has no plan and is written by the walk
//! (`sentence::message_seen`). A hole whose value is `pause` changes the
//! rule's separators: that line is written by the walk too.
//!
//! Invariant: a plan's line is byte for byte the walk's of the same
//! pattern and holes (the rule is `sentence::rule`, the one the walk
//! runs; an item's text is `sentence::write_seen`'s). A plan is kept only
//! for a pattern in a store's frozen region (its cells never change nor
//! move), by the pattern's place, for one store at a time
//! (`Store`'s identity: another store's plans are dropped).

use crate::hash::AtomKeyMap;
use crate::sentence::{pause_atom, rule, write_seen, Holed, Said};
use crate::store::Store;
use crate::term::{Repr, Term};
use sitlog_syntax::atoms;

/// One piece of a planned line.
#[derive(Clone, Copy, Debug)]
enum Piece {
    /// Text of [`Plans::text`], from..to.
    Text(u32, u32),
    /// The value of hole `i`.
    Hole(u32),
}

/// The planned lines of one store's `say` patterns (module doc).
#[derive(Default)]
pub(super) struct Plans {
    /// The store the plans are of (`Store::id`).
    store: u64,
    /// By the pattern's place: its pieces (`pieces[from..to]`), or `None`
    /// where it has no plan.
    by_pattern: AtomKeyMap<u32, Option<(u32, u32)>>,
    /// The last pattern's place and plan (a `say` at each step of a walk:
    /// the same pattern again).
    last: Option<(u32, Option<(u32, u32)>)>,
    pieces: Vec<Piece>,
    text: String,
}

impl Plans {
    /// Appends to `line` the line of `say` pattern `pattern` (dereferenced,
    /// a marked compound `say(M)`) with `holes` (each atomic), where it
    /// has a plan: `false` (nothing appended) where it has none or a hole
    /// is `pause`.
    #[inline]
    pub(super) fn write(
        &mut self,
        store: &Store,
        pattern: Term,
        holes: &[Term],
        line: &mut String,
    ) -> bool {
        let Some(at) = store.frozen_index(pattern) else {
            return false;
        };
        if self.store != store.id.0 {
            self.by_pattern.clear();
            self.last = None;
            self.pieces.clear();
            self.text.clear();
            self.store = store.id.0;
        }
        let planned = match self.last {
            Some((last, p)) if last == at => p,
            _ => {
                let p = match self.by_pattern.get(&at) {
                    Some(&p) => p,
                    None => {
                        let p = self.plan(store, pattern);
                        self.by_pattern.insert(at, p);
                        p
                    }
                };
                self.last = Some((at, p));
                p
            }
        };
        let Some((from, to)) = planned else {
            return false;
        };
        let start = line.len();
        let pause = Term::atom(pause_atom());
        let src = Holed::new(store, holes);
        for p in &self.pieces[from as usize..to as usize] {
            match *p {
                Piece::Text(a, b) => line.push_str(&self.text[a as usize..b as usize]),
                Piece::Hole(i) => match holes.get(i as usize).map(|&h| store.deref(h)) {
                    Some(h) if h != pause => write_seen(&src, h, line),
                    // The rule's separators change with `pause`; a hole
                    // with no value is written as the term it is.
                    _ => {
                        line.truncate(start);
                        return false;
                    }
                },
            }
        }
        true
    }

    /// How many patterns have a plan (the tests').
    #[cfg(test)]
    pub(super) fn planned(&self) -> usize {
        self.by_pattern.values().filter(|p| p.is_some()).count()
    }

    /// The plan of `say` pattern `pattern` (module doc): its pieces' range
    /// in `pieces`, `None` where it has none.
    fn plan(&mut self, store: &Store, pattern: Term) -> Option<(u32, u32)> {
        let (_, args, _) = store.parts_flagged(pattern)?;
        let &[m] = args else { return None };
        let m = store.deref(m);
        let (from, text_from) = (self.pieces.len(), self.text.len());
        let mut plan = Planner {
            plans: self,
            from,
            text_from,
            start: text_from,
        };
        plan.text("Golem says: ");
        if let Some(i) = hole(store, m) {
            plan.hole(i);
        } else {
            // A proper list of holes and constant items.
            let mut items = Vec::new();
            let mut cur = m;
            while let Some((atoms::DOT, &[head, tail], holed)) = store.parts_flagged(cur) {
                let head = store.deref(head);
                items.push(match hole(store, head) {
                    Some(i) if holed => Item::Hole(i),
                    _ if holed && store.is_holed(head) => return plan.abandon(),
                    _ => Item::Const(head),
                });
                cur = store.deref(tail);
                if holed && store.is_holed(cur) && hole(store, cur).is_some() {
                    return plan.abandon();
                }
            }
            if cur != Term::NIL || items.is_empty() {
                return plan.abandon();
            }
            let pause = Term::atom(pause_atom());
            let src = Holed::plain(store);
            let mut items = items.into_iter();
            let Some(first) = items.next() else {
                return plan.abandon();
            };
            rule(
                first,
                items,
                |x| matches!(x, Item::Const(t) if t == pause),
                |x, plan: &mut Planner<'_>| match x {
                    Item::Const(t) => {
                        write_seen(&src, t, &mut plan.plans.text);
                    }
                    Item::Hole(i) => plan.hole(i),
                },
                &mut plan,
            );
        }
        plan.text("\n");
        Some(plan.finish())
    }
}

/// An item of a planned list.
#[derive(Clone, Copy)]
enum Item {
    Const(Term),
    Hole(u32),
}

/// A plan being made: pieces appended to [`Plans`] from `from`, its text
/// from `text_from`, the text not yet a piece from `start`.
struct Planner<'p> {
    plans: &'p mut Plans,
    from: usize,
    text_from: usize,
    start: usize,
}

impl Planner<'_> {
    /// The text so far a piece, then a place for hole `i`.
    fn hole(&mut self, i: u32) {
        self.close();
        self.plans.pieces.push(Piece::Hole(i));
    }

    fn close(&mut self) {
        let end = self.plans.text.len();
        if end > self.start {
            self.plans
                .pieces
                .push(Piece::Text(self.start as u32, end as u32));
        }
        self.start = end;
    }

    fn finish(mut self) -> (u32, u32) {
        self.close();
        (self.from as u32, self.plans.pieces.len() as u32)
    }

    /// No plan: what was made of it dropped.
    fn abandon(self) -> Option<(u32, u32)> {
        self.plans.pieces.truncate(self.from);
        self.plans.text.truncate(self.text_from);
        None
    }
}

impl Said for Planner<'_> {
    fn text(&mut self, text: &str) {
        self.plans.text.push_str(text);
    }
}

/// The index of hole `t` (dereferenced): a marked compound of one integer
/// argument (`sentence::Holed`'s reading).
fn hole(store: &Store, t: Term) -> Option<u32> {
    match store.holed_parts(t)? {
        (_, &[i]) => match store.deref(i).0 {
            Repr::Int(i) => u32::try_from(i).ok(),
            _ => None,
        },
        _ => None,
    }
}
