//! The native stack of a compiled program: the driver that runs native
//! frames (`nat_drive`), the frames below the running one as its code sees
//! them ([`NatBelow`]) and the hand-over that makes them machine frames
//! (`nat_materialize`), generic over the program's frame type
//! ([`NatFrames`], its `enum NatFrame`: a variant per native DM). Generated
//! code implements [`NatFrames`] by a dispatch to each DM's module; what
//! does not depend on the DMs is written once here, monomorphized in the
//! program's crate (the same machine code as when it was generated per
//! program).
//!
//! The driver keeps an explicit stack of native frames, each run where it
//! lies: a callee runs where the driver holds it and, at a final reached
//! without calling, its caller resumes at once with a reference to it (a
//! call and its return in one turn, nothing pushed); a callee that calls in
//! turn is pushed, and its final resumes the caller with a reference to it,
//! then pops it (or gives its slot to the caller's next call, made at once:
//! without drop code when the finished callee's DM holds nothing to drop,
//! [`NatFrames::replace_done`]); the depth room read from the machine once,
//! again only once the frames below became its own; no frame moved out and
//! back per step, no Rust recursion per nested DM, no term built.
//!
//! Invariant: the machine's DM stack is the native stack's bottom frame
//! (the DM the machine entered) and what is below it; native code reads or
//! writes the machine's frames only after [`nat_materialize`] (every native
//! frame below the running one made a machine frame, waiting in its
//! recursive situation as the interpreter's would, `Cx::wait_template`,
//! bottom first) and after writing its locals back.

use super::{Cx, DmProgram, Fault, RunError, SitIx, Step, TypedRun};
use crate::machine::{AsTerm, IdArg};
use crate::{Store, Term};

/// A program's native frames (its `enum NatFrame`, a variant per native
/// DM): what the driver asks of a frame, each a dispatch to the frame's DM.
pub trait NatFrames<P: DmProgram>: Sized {
    /// Runs the frame (`ret`: the callee it waited for, at its final)
    /// until it calls a DM (`call` set), ends in a final below the base
    /// (`None`, no `call`), or hands over to the machine (`Some(step)`).
    fn step(
        &mut self,
        p: &P,
        cx: &mut Cx<'_, '_, P>,
        ret: Option<&mut Self>,
        stack: &mut NatBelow<'_, Self>,
        call: &mut Option<Self>,
        run: &TypedRun,
    ) -> Result<Option<Step>, RunError>;
    /// The frame's DM call, as a term (from its parameters): the call
    /// term of the history level a push opens (`Cx::push_level`).
    fn call_term(&self, p: &P, cx: &mut Cx<'_, '_, P>) -> Term;
    /// `*self = next`, `self` a frame that reached its final (without
    /// drop code for a DM whose frame holds nothing to drop).
    fn replace_done(&mut self, next: Self);
    /// The frame, waiting for its callee, made the machine's, the callee's
    /// pushed.
    fn wait(&self, p: &P, cx: &mut Cx<'_, '_, P>) -> Result<(), RunError>;
}

/// A native DM's situations (its `enum Nat`: a variant per situation and
/// per recursive situation waiting for its callee, `W<n>`): the id of the
/// situation a variant is at, and where a waiting variant waits. Generated
/// code implements the first two; [`NatAt::nat_wait`] is the same for
/// every DM (a DM with locals writes them back first, in its own
/// `nat_wait`).
pub trait NatAt<P: DmProgram> {
    /// The variant's situation id, as a term.
    fn id_term(&self, p: &P, store: &mut Store) -> Term;
    /// A waiting variant's situation and the pipe value the variant keeps
    /// (the exit arcs read it: the template instance's `in_arg`); `None`
    /// for a variant that waits for no DM (the default: a DM without
    /// waiting variants).
    fn waits(&self) -> Option<(SitIx, Option<&dyn AsTerm>)> {
        None
    }
    /// The frame at this variant, waiting for its callee, made the
    /// machine's (`Cx::wait_template`): the pipe value made a term first,
    /// then the id.
    fn nat_wait(&self, p: &P, cx: &mut Cx<'_, '_, P>) -> Result<(), RunError> {
        let Some((sit, in_arg)) = self.waits() else {
            return Err(cx.fault(Fault::WaitsForNone));
        };
        let in_arg = in_arg.map(|v| v.as_term(cx.store()));
        let id = self.id_term(p, cx.store());
        cx.wait_held(sit, id, in_arg, self.held())
    }
    /// The call a waiting variant's native call evaluated and keeps
    /// (`Cx::wait_held`); `None` (the default) where the call was not
    /// evaluated, or is the template's evaluated again.
    fn held(&self) -> Option<Term> {
        None
    }
}

/// The native frames below the running one, bottom first (the base frame,
/// then the pushed ones); `gone` once they were made machine frames
/// ([`nat_materialize`]): the running frame is the native stack's bottom
/// from then on.
pub struct NatBelow<'s, F> {
    base: Option<&'s F>,
    mid: &'s [F],
    gone: &'s mut bool,
    /// `Cx::depth_room` when the driver last looked (the machine's frames
    /// change only when the native ones become theirs, `gone`).
    room: usize,
}

impl<F> NatBelow<'_, F> {
    /// How many native frames are below the running one.
    #[inline]
    pub fn len(&self) -> usize {
        if *self.gone {
            0
        } else {
            usize::from(self.base.is_some()) + self.mid.len()
        }
    }

    /// Whether the running frame is the native stack's bottom.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether a callee's frame may go on the native stack: the frames
    /// below, the running one and the machine's stay within the depth
    /// limit (`Cx::depth_room` asked again once the frames below became the
    /// machine's).
    #[inline]
    pub fn has_room<P: DmProgram>(&self, cx: &Cx<'_, '_, P>) -> bool {
        if *self.gone {
            0 < cx.depth_room()
        } else {
            self.len() < self.room
        }
    }

    /// No exit arc of a waiting situation `sit` (id `id`, filled after the
    /// hand-over) takes its callee's final `final_at`, in a DM without
    /// locals: the frames below made the machine's ([`nat_hand_over`]),
    /// then the machine's error ([`Cx::no_exit`]). One cold call for the
    /// tail of every exit `match` of such a DM.
    #[cold]
    #[inline(never)]
    pub fn no_exit<P: DmProgram, N: NatAt<P>>(
        &mut self,
        p: &P,
        cx: &mut Cx<'_, '_, P>,
        count: u64,
        sit: SitIx,
        id: impl IdArg,
        final_at: &N,
    ) -> Result<Option<Step>, RunError>
    where
        F: NatFrames<P>,
    {
        nat_hand_over(p, cx, self)?;
        let id = id.id_in(cx.store());
        cx.no_exit(count, sit, id, |s| final_at.id_term(p, s))
    }
}

/// Runs native frames from `base` (the DM the machine entered) on an
/// explicit stack until one hands over to the machine. Frames stay where
/// they are while they run (`frames`, above `base`): a callee runs where the
/// driver holds it, and when it reaches its final without calling, its
/// caller's exit arcs read it there at once (a call and its return in one
/// turn of the inner loop, no push, no pop); a callee that calls in turn
/// (or below which the frames became the machine's) is pushed, and a pushed
/// callee that reached its final is read in place by its caller's exit
/// arcs, then popped. Never inlined (into the program's `run_situation`,
/// its caller for an all-native DM: inlined there, its loop measured 2
/// instructions a call more).
#[inline(never)]
pub fn nat_drive<P: DmProgram, F: NatFrames<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    base: F,
    run: &TypedRun,
) -> Result<Step, RunError> {
    let mut base = base;
    let mut frames: Vec<F> = Vec::new();
    let mut call = None;
    // The top frame reached a final: its caller runs next.
    let mut returning = false;
    let mut gone = false;
    // The top frame already ran (a callee run where it is held, below):
    // only what it left is handled.
    let mut ran = false;
    let mut room = cx.depth_room();
    loop {
        if !ran {
            let n = frames.len();
            let stepped = match (n, returning) {
                (0, _) => {
                    let mut below = NatBelow {
                        base: None,
                        mid: &[],
                        gone: &mut gone,
                        room,
                    };
                    base.step(p, cx, None, &mut below, &mut call, run)
                }
                (1, true) => {
                    let mut below = NatBelow {
                        base: None,
                        mid: &[],
                        gone: &mut gone,
                        room,
                    };
                    base.step(p, cx, frames.last_mut(), &mut below, &mut call, run)
                }
                (_, true) => {
                    let (callee, rest) = frames.split_last_mut().unwrap();
                    let (top, mid) = rest.split_last_mut().unwrap();
                    let mut below = NatBelow {
                        base: Some(&base),
                        mid,
                        gone: &mut gone,
                        room,
                    };
                    top.step(p, cx, Some(callee), &mut below, &mut call, run)
                }
                (_, false) => {
                    let (top, mid) = frames.split_last_mut().unwrap();
                    let mut below = NatBelow {
                        base: Some(&base),
                        mid,
                        gone: &mut gone,
                        room,
                    };
                    top.step(p, cx, None, &mut below, &mut call, run)
                }
            };
            if let Some(step) = stepped? {
                return Ok(step);
            }
            if returning {
                returning = false;
                // The caller called again (a loop of calls): the new callee
                // takes the finished one's place.
                if !gone {
                    if let Some(callee) = call.take() {
                        if let Some(top) = frames.last_mut() {
                            *top = callee;
                        }
                        continue;
                    }
                }
                frames.pop();
            }
        }
        ran = false;
        if gone {
            // The frames below the running one are the machine's now.
            if let Some(top) = frames.pop() {
                base = top;
            }
            frames.clear();
            gone = false;
            room = cx.depth_room();
        }
        let Some(mut callee) = call.take() else {
            if frames.is_empty() {
                return Err(cx.error("native code ended its base DM without handing over", None));
            }
            returning = true;
            continue;
        };
        // The callee runs where it is held, not pushed: when it reaches its
        // final without calling, its caller resumes reading it at once (one
        // turn per call, no push, no pop).
        loop {
            let stepped = {
                let mut below = NatBelow {
                    base: Some(&base),
                    mid: &frames,
                    gone: &mut gone,
                    room,
                };
                callee.step(p, cx, None, &mut below, &mut call, run)
            };
            if let Some(step) = stepped? {
                return Ok(step);
            }
            if gone || call.is_some() {
                // It called in turn, or the frames below are the machine's:
                // it is the top frame that ran.
                frames.push(callee);
                break;
            }
            let stepped = match frames.split_last_mut() {
                None => {
                    let mut below = NatBelow {
                        base: None,
                        mid: &[],
                        gone: &mut gone,
                        room,
                    };
                    base.step(p, cx, Some(&mut callee), &mut below, &mut call, run)
                }
                Some((top, mid)) => {
                    let mut below = NatBelow {
                        base: Some(&base),
                        mid,
                        gone: &mut gone,
                        room,
                    };
                    top.step(p, cx, Some(&mut callee), &mut below, &mut call, run)
                }
            };
            if let Some(step) = stepped? {
                return Ok(step);
            }
            if !gone {
                if let Some(next) = call.take() {
                    // A loop of calls: the next callee is held where the
                    // finished one was.
                    callee.replace_done(next);
                    continue;
                }
            }
            // The caller is the top frame that ran; its finished callee is
            // dropped.
            break;
        }
        ran = true;
    }
}

/// Before the running frame hands over: the frames below made the
/// machine's ([`nat_materialize`]). A DM with locals writes them back
/// after it, in its own `nat_hand_over`.
#[cold]
#[inline(never)]
pub fn nat_hand_over<P: DmProgram, F: NatFrames<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    stack: &mut NatBelow<'_, F>,
) -> Result<(), RunError> {
    nat_materialize(p, cx, stack)
}

/// Which arc's expectation the perception meets (`Cx::choose_kept`), the
/// frames below kept native unless the machine reads them (an input that
/// meets nothing, an error, a prompt told where it waits): then handed
/// over first ([`nat_hand_over`]), in a DM without locals.
#[inline]
pub fn nat_choose<P: DmProgram, F: NatFrames<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    stack: &mut NatBelow<'_, F>,
    type_term: Term,
) -> Result<Option<usize>, RunError> {
    cx.choose_kept(type_term, |cx| nat_hand_over(p, cx, stack))
}

/// The end of a native step that gives the machine control (garbage to
/// collect, a stop asked: `Cx::gc_tick`) in a DM without locals: the
/// frames below made the machine's ([`nat_hand_over`]), then
/// `Cx::step_goto` to `at`, the situation reached, as its id.
#[cold]
#[inline(never)]
pub fn nat_goto<P: DmProgram, F: NatFrames<P>, N: NatAt<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    stack: &mut NatBelow<'_, F>,
    count: u64,
    at: &N,
) -> Result<Option<Step>, RunError> {
    nat_hand_over(p, cx, stack)?;
    cx.step_goto(count, |s| at.id_term(p, s))
}

/// A visit handed to its template in a DM without locals: the frames
/// below made the machine's ([`nat_hand_over`]), then
/// [`Cx::counted_template`] of situation `sit` with its id (filled after
/// the hand-over, as where the two are written one after the other).
#[cold]
#[inline(never)]
pub fn nat_template<P: DmProgram, F: NatFrames<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    stack: &mut NatBelow<'_, F>,
    count: u64,
    sit: SitIx,
    id: impl IdArg,
) -> Result<Option<Step>, RunError> {
    nat_hand_over(p, cx, stack)?;
    cx.counted_template(count, sit, id)
}

/// Makes the native frames below the running one machine frames, bottom
/// first: each waits in its recursive situation, its callee's frame
/// pushed with the call its situation's `embedded_dm` makes
/// (`Cx::wait_template`), as the machine's call pushes it; so no call
/// term is built from a native frame's parameters here, and the DMs are
/// those the calls name.
pub fn nat_materialize<P: DmProgram, F: NatFrames<P>>(
    p: &P,
    cx: &mut Cx<'_, '_, P>,
    stack: &mut NatBelow<'_, F>,
) -> Result<(), RunError> {
    if stack.is_empty() {
        return Ok(());
    }
    *stack.gone = true;
    for f in stack.base.into_iter().chain(stack.mid.iter()) {
        f.wait(p, cx)?;
    }
    Ok(())
}

/// Whether a DM's frame (of type `T`) holds nothing to drop: a constant
/// per DM, for [`nat_replace_done`].
#[inline(always)]
pub fn nat_plain<T>(_frame: &T) -> bool {
    !std::mem::needs_drop::<T>()
}

/// `*slot = next`, `slot` a frame that reached its final
/// ([`NatFrames::replace_done`]): without drop code when its DM's frame
/// holds nothing to drop (`plain`, [`nat_plain`] of the frame's DM).
#[inline(always)]
pub fn nat_replace_done<F>(slot: &mut F, next: F, plain: bool) {
    if plain {
        std::mem::forget(std::mem::replace(slot, next));
    } else {
        *slot = next;
    }
}
