//! The dispatcher: a service or update call written as a Prolog term (KB
//! argument left out, answer last) → checked against the service tables →
//! run. Owns the answer type, whose terms live on top of the KB's store.

use crate::closure::{Budget, PE};
use crate::entry::{ARROW, NOT};
use crate::model::Kb;
use crate::services::{service, Arg};
use crate::store::{Built, TId};
use crate::update::update_service;
use sitlog_syntax::write::{TermSource, View};
use sitlog_syntax::{Clause, Node, Span, SyntaxError, TermId};
use std::fmt;

/// The answer term of a service call.
#[derive(Clone, Debug)]
pub struct Answer<'k> {
    built: Built<'k>,
    root: TId,
}

impl<'k> Answer<'k> {
    /// The answer as `writeq` prints it (SitLog operators).
    pub fn writeq(&self) -> String {
        self.built.writeq(self.root)
    }
    /// The answer's root, to walk it through [`Answer::source`].
    pub fn root(&self) -> TId {
        self.root
    }
    /// The terms, one level at a time (for converting to other term types).
    pub fn source(&self) -> &Built<'k> {
        &self.built
    }
}

impl fmt::Display for Answer<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.writeq())
    }
}

impl TermSource for Answer<'_> {
    type Ref = TId;
    fn view(&self, term: TId) -> View<'_, TId> {
        self.built.view(term)
    }
}

/// What a service call gives: an answer, or failure (the original's call fails).
#[derive(Clone, Debug)]
pub enum Outcome<'k> {
    Answer(Answer<'k>),
    Fails,
}

impl Outcome<'_> {
    /// The `sitlogc kb` output line: the answer, or `false`.
    pub fn to_line(&self) -> String {
        match self {
            Outcome::Answer(a) => a.writeq(),
            Outcome::Fails => "false".to_owned(),
        }
    }
}

/// Why a call could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum CallError {
    Syntax(SyntaxError),
    /// Not a compound or atom naming a service.
    NotCallable(Span),
    UnknownService {
        name: String,
        arity: usize,
        span: Span,
    },
    /// The answer (last argument) is not a variable.
    AnswerNotVar(Span),
    /// An input argument contains a variable.
    NotGround(Span),
    /// The closure needed more steps than allowed.
    Budget(Span),
}

impl CallError {
    pub fn span(&self) -> Span {
        match self {
            CallError::Syntax(e) => e.span,
            CallError::NotCallable(s)
            | CallError::AnswerNotVar(s)
            | CallError::NotGround(s)
            | CallError::Budget(s) => *s,
            CallError::UnknownService { span, .. } => *span,
        }
    }
}

impl fmt::Display for CallError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CallError::Syntax(e) => write!(f, "{}", e.message),
            CallError::NotCallable(_) => f.write_str(
                "expected a service call such as object_property_value(ana, found_in, X)",
            ),
            CallError::UnknownService { name, arity, .. } => {
                write!(f, "unknown KB service {name}/{arity}")
            }
            CallError::AnswerNotVar(_) => {
                f.write_str("the answer (last argument) must be a variable")
            }
            CallError::NotGround(_) => {
                f.write_str("arguments other than the answer must not contain variables")
            }
            CallError::Budget(_) => {
                f.write_str("the closure needs too many steps (exponential forward chaining)")
            }
        }
    }
}

impl std::error::Error for CallError {}

fn callable(c: &Clause) -> Result<(String, Vec<TermId>), CallError> {
    let root = c.root;
    match c.terms.node(root) {
        Node::Atom(a) => Ok((a.as_str().to_owned(), Vec::new())),
        Node::Compound { functor, .. } => {
            Ok((functor.as_str().to_owned(), c.terms.args(root).to_vec()))
        }
        _ => Err(CallError::NotCallable(c.terms.span(root))),
    }
}

fn name_span(c: &Clause) -> Span {
    let s = c.terms.span(c.root);
    let len = match c.terms.node(c.root) {
        Node::Atom(a) | Node::Compound { functor: a, .. } => a.as_str().len() as u32,
        _ => 0,
    };
    Span {
        start: s.start,
        end: s.start + len.max(1),
    }
}

fn has_var(c: &Clause, t: TermId) -> Option<Span> {
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        match c.terms.node(t) {
            Node::Var(_) => return Some(c.terms.span(t)),
            Node::Compound { .. } => stack.extend_from_slice(c.terms.args(t)),
            _ => {}
        }
    }
    None
}

impl Kb {
    fn arg(&self, c: &Clause, t: TermId) -> Result<Arg, CallError> {
        let terms = &c.terms;
        let find = |t: TermId| -> Result<Option<TId>, CallError> {
            self.store.find(c, t).map_err(CallError::NotGround)
        };
        let whole = find(t)?;
        let pe = match terms.compound(t, ARROW, 2) {
            Some([a, b]) => match (find(*a)?, find(*b)?) {
                (Some(a), Some(b)) => Some(PE::Arrow(a, b)),
                _ => None,
            },
            _ => whole.map(PE::T),
        };
        let not_inner = match terms.compound(t, NOT, 1) {
            Some([x]) => Some(find(*x)?),
            _ => None,
        };
        Ok(Arg {
            t: whole,
            pe,
            not_inner,
        })
    }

    /// Checks a query term and finds its service (no KB needed).
    pub fn check_query(c: &Clause) -> Result<(), CallError> {
        let (name, args) = callable(c)?;
        let Some(_) = service(&name, args.len()) else {
            return Err(CallError::UnknownService {
                name,
                arity: args.len(),
                span: name_span(c),
            });
        };
        let (last, inputs) = args
            .split_last()
            .ok_or(CallError::NotCallable(c.terms.span(c.root)))?;
        if !matches!(c.terms.node(*last), Node::Var(_)) {
            return Err(CallError::AnswerNotVar(c.terms.span(*last)));
        }
        for &a in inputs {
            if let Some(s) = has_var(c, a) {
                return Err(CallError::NotGround(s));
            }
        }
        Ok(())
    }

    /// Checks an update term and finds its service (no KB needed).
    pub fn check_update(c: &Clause) -> Result<(), CallError> {
        let (name, args) = callable(c)?;
        if update_service(&name, args.len()).is_none() {
            return Err(CallError::UnknownService {
                name,
                arity: args.len(),
                span: name_span(c),
            });
        }
        for &a in &args {
            if let Some(s) = has_var(c, a) {
                return Err(CallError::NotGround(s));
            }
        }
        Ok(())
    }

    /// Calls a service: `service(Args..., Answer)` without the KB argument.
    pub fn call(&self, c: &Clause) -> Result<Outcome<'_>, CallError> {
        Kb::check_query(c)?;
        let (name, args) = callable(c)?;
        let svc = service(&name, args.len()).ok_or(CallError::NotCallable(c.span))?;
        let inputs = &args[..args.len() - 1];
        let parsed = inputs
            .iter()
            .map(|&t| self.arg(c, t))
            .collect::<Result<Vec<_>, _>>()?;
        let mut b = Built::new(&self.store);
        match (svc.run)(self, &parsed, &mut b) {
            Ok(Some(root)) => Ok(Outcome::Answer(Answer { built: b, root })),
            Ok(None) => Ok(Outcome::Fails),
            Err(Budget) => Err(CallError::Budget(c.terms.span(c.root))),
        }
    }

    /// Reads and calls a service written as text.
    pub fn query(&self, src: &str) -> Result<Outcome<'_>, CallError> {
        let c = sitlog_syntax::read_term(src).map_err(CallError::Syntax)?;
        // The answer borrows only the KB, not the clause.
        self.call(&c)
    }

    /// Applies an update: `update(Args...)` without the two KB arguments.
    /// `Ok(false)`: the update fails (as in the original, or because it would
    /// break the KB's invariants); the KB is then unchanged.
    pub fn update(&mut self, c: &Clause) -> Result<bool, CallError> {
        Kb::check_update(c)?;
        let (name, args) = callable(c)?;
        let svc = update_service(&name, args.len()).ok_or(CallError::NotCallable(c.span))?;
        let mut ids = Vec::with_capacity(args.len());
        for &a in &args {
            ids.push(self.store.intern(c, a).map_err(CallError::NotGround)?);
        }
        Ok((svc.run)(self, &ids))
    }

    /// Reads and applies an update written as text.
    pub fn apply(&mut self, src: &str) -> Result<bool, CallError> {
        let c = sitlog_syntax::read_term(src).map_err(CallError::Syntax)?;
        self.update(&c)
    }
}
