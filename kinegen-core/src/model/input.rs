//! The shape of a robot description, shared by both front ends.
//!
//! [`crate::model::validate`] checks the DH table itself; this module holds what surrounds it: the
//! top-level keys and the `budget` entries. The `kinematics!` macro and the TOML loader
//! both take their messages from here, so the same mistake reads the same in both.

use crate::model::options::Budget;
use crate::model::raw::{DhError, PathSeg};

/// Keys allowed at the top level of a robot description.
pub const TOP_LEVEL_KEYS: &[&str] = &[
    "name",
    "convention",
    "params",
    "joints",
    "task",
    "base",
    "tool",
    "scalar",
    "budget",
    "ik_free",
];

/// Keys allowed in `budget`.
pub const BUDGET_KEYS: &[&str] = &["nodes", "iterations", "time_ms"];

/// Message for a top-level key that is not in [`TOP_LEVEL_KEYS`].
pub fn unknown_top_level_key(key: &str) -> String {
    format!(
        "unknown key `{key}`: expected name, convention, params, joints, task, base, tool, scalar, budget or ik_free"
    )
}

/// Message for an entry given twice.
pub fn given_twice(key: &str) -> String {
    format!("`{key}` given twice")
}

/// `ik_free` as written: the joint (1-based, as in the table) a 7-joint arm's closed-form
/// IK leaves free. `value` is the entry as an integer, `None` if it is not one.
///
/// ```
/// use kinegen_core::model::input::ik_free_value;
/// assert_eq!(ik_free_value(Some(7)), Ok(7));
/// assert!(ik_free_value(Some(0)).is_err());
/// assert!(ik_free_value(None).is_err());
/// ```
pub fn ik_free_value(value: Option<i128>) -> Result<usize, String> {
    match value {
        Some(k) if (1..=64).contains(&k) => Ok(k as usize),
        _ => Err(
            "`ik_free` is the number of the joint the closed-form IK leaves free, e.g. `7`".into(),
        ),
    }
}

/// `ik_free = k` (1-based) against the robot's joint count: the joint, 0-based, or why
/// it cannot be (only a 7-joint arm leaves a joint free).
///
/// ```
/// use kinegen_core::model::input::check_ik_free;
/// assert_eq!(check_ik_free(7, 7), Ok(6));
/// assert!(check_ik_free(8, 7).is_err());
/// assert!(check_ik_free(3, 6).is_err());
/// ```
pub fn check_ik_free(k: usize, dof: usize) -> Result<usize, String> {
    if dof != 7 {
        return Err(format!(
            "`ik_free` is for a 7-joint arm, whose closed-form IK leaves one joint free; this one has {dof} joints"
        ));
    }
    if k == 0 || k > dof {
        return Err(format!(
            "`ik_free` names joint {k}: the arm has joints 1 to {dof}"
        ));
    }
    Ok(k - 1)
}

/// Set one `budget` entry. `value` is the entry as an integer, `None` if it is not one.
///
/// ```
/// use kinegen_core::{model::input::set_budget, Budget};
/// let mut b = Budget::default();
/// set_budget(&mut b, "nodes", Some(2000)).unwrap();
/// assert_eq!(b.nodes, 2000);
/// assert!(set_budget(&mut b, "nodes", Some(0)).is_err());
/// assert!(set_budget(&mut b, "depth", Some(3)).is_err());
/// ```
pub fn set_budget(budget: &mut Budget, key: &str, value: Option<i128>) -> Result<(), String> {
    if !BUDGET_KEYS.contains(&key) {
        return Err(format!(
            "unknown budget entry `{key}`: expected nodes, iterations or time_ms"
        ));
    }
    // Zero would make the engine do nothing; the upper bound keeps `usize` casts exact.
    let n = match value {
        Some(n) if n > 0 && n <= i128::from(u32::MAX) => n as u64,
        _ => {
            return Err(format!(
                "`{key}` must be a positive integer (at most {})",
                u32::MAX
            ))
        }
    };
    match key {
        "nodes" => budget.nodes = n as usize,
        "iterations" => budget.iterations = n as usize,
        _ => budget.time_ms = n,
    }
    Ok(())
}

/// All errors of one input: `shape` errors found while reading it (wrong kinds of
/// entries, unknown keys) then `checks` from [`crate::model::validate::validate`], minus the checks
/// under a top-level key that already has a shape error (a `joints` entry that is not a
/// list would otherwise also report "the DH table has no joints").
pub fn combine_errors(shape: Vec<DhError>, checks: Vec<DhError>) -> Vec<DhError> {
    let top = |e: &DhError| match e.path.0.first() {
        Some(PathSeg::Key(k)) => Some(k.clone()),
        _ => None,
    };
    let broken: Vec<String> = shape.iter().filter_map(top).collect();
    let mut out = shape;
    out.extend(
        checks
            .into_iter()
            .filter(|e| top(e).is_none_or(|k| !broken.contains(&k))),
    );
    out
}
