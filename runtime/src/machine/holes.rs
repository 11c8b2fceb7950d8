//! The holes of a pattern native code fills ([`Fill`](super::Fill),
//! [`Of`](super::Of), the holes of [`Cx::nat_empty`](super::Cx::nat_empty))
//! as a call that needs them only on a gated or cold path takes them
//! (issue 37): a tuple of references to native values, `(&r5, r6, &r7)`,
//! which is a few pointers the call's inlined test keeps in registers, so
//! a run that neither records nor performs `empty` does no work for them;
//! a slice of `&dyn AsTerm` (`&[&r5, r6, &r7]`) is built in memory (each
//! value's address and vtable stored) before the test, at every step.
//! A slice is still one (code that fills at once, more than twelve holes).
//!
//! Invariant: [`Holes::with_terms`] makes each hole a term in order, first
//! to last, as [`fill`](super::fill) does with a slice, so the store sees
//! the same terms made in the same order whichever form the code gives.

use super::cx::AsTerm;
use crate::store::Store;
use crate::term::Term;

/// The holes of a pattern, made terms only where a call needs them.
pub trait Holes: Copy {
    /// `f` of the holes made terms in `store`, in order.
    fn with_terms<R>(self, store: &mut Store, f: impl FnOnce(&mut Store, &[Term]) -> R) -> R;
}

impl Holes for &[&dyn AsTerm] {
    #[inline]
    fn with_terms<R>(self, store: &mut Store, f: impl FnOnce(&mut Store, &[Term]) -> R) -> R {
        if self.len() <= 8 {
            let mut ts = [Term::NIL; 8];
            for (t, a) in ts.iter_mut().zip(self) {
                *t = a.as_term(store);
            }
            f(store, &ts[..self.len()])
        } else {
            let ts: Vec<Term> = self.iter().map(|a| a.as_term(store)).collect();
            f(store, &ts)
        }
    }
}

/// More holes than a tuple takes, as the code generator writes them: an
/// array whose first element is cast (`&[&r1 as &dyn machine::AsTerm, ..]`).
impl<const N: usize> Holes for &[&dyn AsTerm; N] {
    #[inline]
    fn with_terms<R>(self, store: &mut Store, f: impl FnOnce(&mut Store, &[Term]) -> R) -> R {
        (self as &[&dyn AsTerm]).with_terms(store, f)
    }
}

impl Holes for () {
    #[inline]
    fn with_terms<R>(self, store: &mut Store, f: impl FnOnce(&mut Store, &[Term]) -> R) -> R {
        f(store, &[])
    }
}

macro_rules! tuple_holes {
    ($($t:ident $i:tt),+) => {
        impl<$($t: AsTerm),+> Holes for ($(&$t,)+) {
            #[inline]
            fn with_terms<R>(
                self,
                store: &mut Store,
                f: impl FnOnce(&mut Store, &[Term]) -> R,
            ) -> R {
                let ts = [$(self.$i.as_term(store)),+];
                f(store, &ts)
            }
        }
    };
}

tuple_holes!(A 0);
tuple_holes!(A 0, B 1);
tuple_holes!(A 0, B 1, C 2);
tuple_holes!(A 0, B 1, C 2, D 3);
tuple_holes!(A 0, B 1, C 2, D 3, E 4);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10);
tuple_holes!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10, L 11);

/// The most holes the code generator gives as a tuple.
pub const TUPLE_HOLES: usize = 12;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::Val;

    #[test]
    fn a_tuple_and_a_slice_make_the_same_terms_in_order() {
        let mut s = Store::new();
        let (a, b) = (Val::Int(1), 2i64);
        let slice: &[&dyn AsTerm] = &[&a, &b];
        let x = slice.with_terms(&mut s, |_, ts| ts.to_vec());
        let y = (&a, &b).with_terms(&mut s, |_, ts| ts.to_vec());
        assert_eq!(x, y);
        assert_eq!(x, vec![Term::int(1), Term::int(2)]);
        assert!(().with_terms(&mut s, |_, ts| ts.is_empty()));
        let arr: &[&dyn AsTerm; 2] = &[&a as &dyn AsTerm, &b];
        assert_eq!(arr.with_terms(&mut s, |_, ts| ts.to_vec()), x);
    }
}
