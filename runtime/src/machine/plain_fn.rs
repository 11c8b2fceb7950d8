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
use crate::plain::rt::Answer;
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
    /// engine's form is `form`: `crate::plain::slots`), on the arguments
    /// by reference; elsewhere the call is [`Cx::nat_plain`]'s, its value
    /// the answer [`Answer::of_val`] (also where the compiled function
    /// answers `None`: a float its arithmetic on integers does not take).
    /// `None`: evaluate the `apply` as a term.
    #[inline]
    pub fn nat_plain_rs<'v, const N: usize, R: Answer>(
        &mut self,
        k: usize,
        name: Atom,
        form: &str,
        args: [&'v Val; N],
        f: impl FnOnce([&'v Val; N]) -> Option<R>,
    ) -> Option<R> {
        let m = &mut *self.m;
        match m
            .plain_slots
            .run(k, &m.functions, &m.store, &m.globals, name, form, args, f)
        {
            Some(Some(v)) => Some(v),
            // Not resolved, or the compiled function refused: a function
            // of integers compiled without floats refuses a float the
            // form runs on (`plain::num`), which the form then runs.
            _ => self.nat_plain_other(name, args).map(R::of_val),
        }
    }

    /// [`Cx::nat_plain`] of arguments by reference (a slot not resolved
    /// to its compiled function).
    #[cold]
    #[inline(never)]
    fn nat_plain_other<const N: usize>(&self, name: Atom, args: [&Val; N]) -> Option<Val> {
        self.nat_plain(name, &args.map(Val::clone))
    }
}
