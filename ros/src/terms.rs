//! The terms a robot over ROS 2 reads and makes, outside the DDS calls:
//! an action's arguments (names, hands, numbers), its status argument, a
//! status read from a result, a place's goal pose, a name said inside a
//! sentence.

use crate::config::Interface;
use crate::msgs::*;
use sitlog_runtime::{Store, Term, Value};
use sitlog_sim::Hand;

/// Resolves a place of the interface to a goal pose.
pub(crate) fn goal_pose(iface: &Interface, place: &str) -> Option<NavigateToPoseGoal> {
    let &(x, y, yaw) = iface.places.get(place)?;
    Some(NavigateToPoseGoal {
        pose: PoseStamped {
            header: Header {
                stamp: Time::now(),
                frame_id: iface.frames.map.clone(),
            },
            pose: Pose {
                position: Point { x, y, z: 0.0 },
                orientation: Quaternion::yaw(yaw),
            },
        },
        behavior_tree: String::new(),
    })
}

/// Reads an aborted action's status (`blocked(hall, kitchen)`,
/// `grasp_failed`): a ground term, else `None`.
pub(crate) fn status_term(store: &mut Store, text: &str) -> Option<Term> {
    let text = text.trim();
    if text.is_empty() || !text.starts_with(|c: char| c.is_ascii_lowercase()) {
        return None;
    }
    let (t, _) = store.parse(text).ok()?;
    store.is_ground(t).then_some(t)
}

/// The name an argument gives (an atom), or an error naming the action.
pub(crate) fn name_arg(
    store: &Store,
    action: Term,
    i: usize,
    what: &str,
) -> Result<String, String> {
    let a = store.args(action)[i];
    store
        .atom_of(a)
        .map(|n| n.as_str().to_owned())
        .ok_or_else(|| {
            format!(
                "`{}`: the {what} must be an atom, not `{}`",
                store.writeq(action),
                store.writeq(a)
            )
        })
}

pub(crate) fn hand_arg(store: &Store, action: Term, i: usize) -> Result<Hand, String> {
    let name = name_arg(store, action, i, "hand")?;
    name.parse::<Hand>()
        .map_err(|e| format!("`{}`: {e}", store.writeq(action)))
}

/// Unifies the status argument `i` of `action` with `status`.
pub(crate) fn report(
    store: &mut Store,
    action: Term,
    i: usize,
    status: Term,
) -> Result<(), String> {
    let arg = store.args(action)[i];
    if store.unify(arg, status) {
        Ok(())
    } else {
        Err(format!(
            "`{}`: the robot's answer `{}` does not match",
            store.writeq(action),
            store.writeq(status)
        ))
    }
}

pub(crate) fn number(store: &Store, t: Term) -> Option<f64> {
    match store.value(t) {
        Value::Int(i) => Some(i as f64),
        Value::Float(f) => Some(f),
        _ => None,
    }
}

/// `The manager` → `the manager` (a name said inside a sentence).
pub(crate) fn lower_first(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_lowercase().chain(c).collect(),
        None => String::new(),
    }
}
