//! [`Cx::nat_plain`]: native code calling a user function on the values it
//! holds (issue 37), without building the `apply` term, handing its frames
//! over or converting the value back: what the functions' registry runs on
//! native values ([`crate::functions::NativeFn`], the plain Prolog
//! functions). It reads the store and the globals only and changes
//! nothing, so it needs no frame of the machine's; where it gives `None`
//! the caller takes the term path (`Cx::eval` of the `apply`), whose
//! answer or error it then is. [`Cx::nat_plain_rs`]: the same call of a
//! function compiled into the program, run as compiled where the run's
//! engine holds the form it was compiled from.

use super::program::{Cx, DmProgram};
use crate::native::Val;
use sitlog_syntax::Atom;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// The value of `apply(name(_, ..), [args..])` (each declared argument
    /// a fresh variable taking its value), if the registry runs it on
    /// native values; `None`: evaluate the `apply` as a term. Only for a DM
    /// without locals (the function is given the globals as the caller's
    /// variables), the arguments values L passes on as they are.
    #[inline]
    pub fn nat_plain(&self, name: Atom, args: &[Val]) -> Option<Val> {
        let m = &*self.m;
        m.functions.call_native(&m.store, &m.globals, name, args)
    }
}

impl<P: DmProgram> Cx<'_, '_, P> {
    /// [`Cx::nat_plain`] of a plain function compiled into the program:
    /// `f`, the function compiled from the form whose fingerprint is
    /// `form`, runs where slot `k` resolved to it for this run (the
    /// engine's form is `form`: `crate::plain::slots`); elsewhere the call
    /// is [`Cx::nat_plain`]'s. `None`: evaluate the `apply` as a term.
    #[inline]
    pub fn nat_plain_rs(
        &mut self,
        k: usize,
        name: Atom,
        form: &str,
        args: &[Val],
        f: impl FnOnce(&[Val]) -> Option<Val>,
    ) -> Option<Val> {
        let m = &mut *self.m;
        match m
            .plain_slots
            .run(k, &m.functions, &m.store, &m.globals, name, form, args, f)
        {
            Some(v) => v,
            None => m.functions.call_native(&m.store, &m.globals, name, args),
        }
    }
}
