//! Type tests in a conditional's condition as native code (`number(L) ->
//! wound ; otherwise -> jammed`): `var/1`, `nonvar/1`, `ground/1`,
//! `atom/1`, `number/1`, `integer/1`, `float/1`, `atomic/1`, `compound/1`,
//! `is_list/1` of a register native code holds, and `\+` of one. The
//! machine evaluates the condition's arguments, then calls it as a goal
//! (D-35, `runtime::goal`); a native value is its own value, so the test
//! is decided on the value: from the register's type where the type
//! decides it (an `int` is a number, never an atom), else by
//! `TypeTest::of_val` on a `Val` or `TypeTest::of_term` on a term native
//! code holds (the runtime's `type_test`, the one decider the machine's
//! goal calls too).
//!
//! Invariant: a test native code decides answers as the machine's goal on
//! the register's term would; a register native code does not hold (a
//! fresh variable, one that holds no value) or an argument that is not a
//! register is an error here, and the caller keeps the condition the
//! machine's.

use super::{held_as_val, place, Regs, N};
use crate::codegen::Gen;
use crate::mir::Build;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_runtime::type_test::TypeTest;

impl Gen<'_> {
    /// Whether `b` is a type test native code may decide (`number(X)`,
    /// `\+ atom(X)`, ...), before its register is looked at.
    pub(super) fn is_type_test(&self, b: &Build) -> bool {
        crate::mir::is_type_test(b)
    }

    /// The test of type test `b` ([`Gen::is_type_test`]) as a `bool`
    /// expression on the registers `regs`.
    pub(super) fn nat_type_test(&self, b: &Build, regs: &Regs) -> N<TokenStream> {
        let Build::Compound(op, args) = b else {
            return Err("not a type test".into());
        };
        if op.as_str() == "\\+" && args.len() == 1 {
            let t = self.nat_type_test(&args[0], regs)?;
            return Ok(quote!((!#t)));
        }
        let k = TypeTest::of(op.as_str(), args.len()).ok_or("not a type test")?;
        let [Build::Reg(r)] = &args[..] else {
            return Err(format!(
                "`{}/1` of a value that is not a variable",
                k.name()
            ));
        };
        if regs.get(r).is_some_and(|(v, _)| super::is_fresh(v)) {
            return Err(format!("`{}/1` of a fresh variable", k.name()));
        }
        let v = self.nat_value(&Build::Reg(*r), regs)?;
        if let Some(holds) = static_answer(k, &v.ty) {
            return Ok(if holds { quote!(true) } else { quote!(false) });
        }
        let x = place(&v);
        let kv = format_ident!("{}", format!("{k:?}"));
        Ok(match &v.ty {
            Ty::Sym => quote!((#x == atoms::NIL)),
            Ty::List(_) if matches!(k, TypeTest::Atom | TypeTest::Atomic) => {
                quote!(#x.is_empty())
            }
            Ty::List(_) if k == TypeTest::Compound => quote!((!#x.is_empty())),
            t if held_as_val(t) => quote!(TypeTest::#kv.of_val(&#x, cx.store_ref())),
            Ty::Term => quote!(TypeTest::#kv.of_term(cx.store_ref(), #x.0)),
            t => return Err(format!("`{}/1` of a value of type {t}", k.name())),
        })
    }
}

/// The answer of test `k` on every value of type `ty`, where the type
/// decides it.
fn static_answer(k: TypeTest, ty: &Ty) -> Option<bool> {
    use TypeTest as T;
    match ty {
        Ty::Int => Some(matches!(
            k,
            T::Nonvar | T::Ground | T::Number | T::Integer | T::Atomic
        )),
        Ty::Float => Some(matches!(
            k,
            T::Nonvar | T::Ground | T::Number | T::Float | T::Atomic
        )),
        // `[]` is an atom and a list: `is_list` asks which atom.
        Ty::Sym if k == T::IsList => None,
        Ty::Sym => Some(matches!(k, T::Nonvar | T::Ground | T::Atom | T::Atomic)),
        Ty::List(e) => match k {
            T::Nonvar | T::IsList => Some(true),
            T::Var | T::Number | T::Integer | T::Float => Some(false),
            T::Ground => ground_ty(e).then_some(true),
            T::Atom | T::Atomic | T::Compound => None,
        },
        // A `Val` (any inert ground value, or a compound shape) and a term
        // native code holds: asked at run time; `never` holds nothing.
        _ => None,
    }
}

/// Whether every value of type `ty` is ground with no term inside.
fn ground_ty(ty: &Ty) -> bool {
    match ty {
        // A `Ground` value is a ground term by its conversion.
        Ty::Int | Ty::Float | Ty::Sym | Ty::Never | Ty::Ground => true,
        Ty::List(e) => ground_ty(e),
        Ty::Tagged(_, args) => args.iter().all(ground_ty),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn types_decide_what_they_can() {
        assert_eq!(static_answer(TypeTest::Number, &Ty::Int), Some(true));
        assert_eq!(static_answer(TypeTest::Float, &Ty::Int), Some(false));
        assert_eq!(static_answer(TypeTest::Integer, &Ty::Float), Some(false));
        assert_eq!(static_answer(TypeTest::Atom, &Ty::Sym), Some(true));
        assert_eq!(static_answer(TypeTest::IsList, &Ty::Sym), None);
        let l = Ty::List(Box::new(Ty::Int));
        assert_eq!(static_answer(TypeTest::IsList, &l), Some(true));
        assert_eq!(static_answer(TypeTest::Ground, &l), Some(true));
        assert_eq!(static_answer(TypeTest::Atom, &l), None);
        assert_eq!(static_answer(TypeTest::Var, &Ty::Ground), None);
    }
}
