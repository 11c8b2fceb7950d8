//! A native in_arg that reads the whole pipe into a register (`in_arg ==>
//! L`), where native code holds the pipe ([`HeldPipe`]: an out_arg of
//! native values, `Cx::hold_pipe`, or a value held whole,
//! `Cx::hold_pipe_value`): the register's value read from the held values
//! themselves ([`Native::from_held`]), no term made for the pipe and none
//! converted back (a list handed to a callee by out_arg and read by its
//! in_arg, at each call: `r25_d_filter_out`). The pipe stays held; a later
//! reader of its term makes it then (`Cx::flush_pipe`).
//!
//! Invariant: [`Cx::pipe_as`] gives what `to_native` of the pipe's term
//! (`Cx::pipe_in`) gives, and [`Cx::pipe_converts`] what `converts_to` of
//! it gives: the held values are canonical `Val`s (no term inside, inert,
//! proper lists only as `Val::List`), whose term `from_term` reads back
//! equal (`FromVal`); where `from_held` cannot tell, the term is made and
//! converted as before. A pipe not held is read as before, with no more
//! than the test of its mark (`Cx::flush_pipe`'s).

use super::program::{Cx, DmProgram};
use super::state::HeldPipe;
use crate::native::{Compound, Native, Val};
use crate::term::Repr;
use sitlog_syntax::atoms;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// The pipe as a `T` (`None`: it does not convert): what
    /// `cx.to_native::<T>(cx.pipe_in())` gives, read from the held values
    /// where native code holds the pipe.
    #[inline]
    pub fn pipe_as<T: Native>(&mut self) -> Option<T> {
        if let Repr::Functor(..) = self.pipe.0 {
            return self.held_pipe_as();
        }
        let t = self.m.store.deref(*self.pipe);
        T::from_term(&self.m.store, t)
    }

    /// Whether the pipe converts to a `T`, no value kept: what
    /// `cx.converts_to::<T>(cx.pipe_in())` gives.
    #[inline]
    pub fn pipe_converts<T: Native>(&mut self) -> bool {
        if let Repr::Functor(..) = self.pipe.0 {
            return self.held_pipe_as::<T>().is_some();
        }
        let t = self.m.store.deref(*self.pipe);
        T::converts(&self.m.store, t)
    }

    /// [`Cx::pipe_as`] of the pipe native code holds: from the held
    /// values, else (`from_held` cannot tell) from the term made.
    #[inline(never)]
    fn held_pipe_as<T: Native>(&mut self) -> Option<T> {
        debug_assert!(*self.pipe == HeldPipe::MARK, "a header cell as the pipe");
        if let Some(v) = self.held_pipe_read::<T>() {
            return Some(v);
        }
        let t = self.pipe_in();
        self.to_native::<T>(t)
    }

    /// `T::from_held` of the held pipe: the value held whole, or
    /// `name(args..)` as the canonical compound of its arguments (not
    /// `'.'/2`, whose term is a list cell).
    fn held_pipe_read<T: Native>(&self) -> Option<T> {
        let h = &self.m.held;
        debug_assert!(
            h.args[..h.n.max(1)].iter().all(|v| !v.holds_terms()),
            "a held pipe holds no term"
        );
        match h.n {
            0 => T::from_held(&h.args[0]),
            2 if h.name == atoms::DOT => None,
            n => T::from_held(&Val::Tagged(Compound::new(
                h.name,
                h.args[..n].iter().cloned(),
            ))),
        }
    }
}
