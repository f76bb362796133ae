//! Which closed-form family a chain belongs to, decided exactly from its axes at `q = 0`
//! ([`Axes`]), and the derivation: which subproblem gives which joint.
//!
//! Families (IK-Geo's names; all quadratics at most):
//!
//! | family | condition | robots |
//! |---|---|---|
//! | three parallel, two intersecting | h2 ∥ h3 ∥ h4, h5 ∩ h6 | UR3/5/10, e-series |
//! | spherical wrist, two parallel | h4, h5, h6 meet; h2 ∥ h3 | PUMA 560, KUKA KR, ABB IRB |
//! | spherical wrist, two intersecting | h4, h5, h6 meet; h1 ∩ h2 | (iiwa with joint 3 locked) |
//! | spherical wrist, two intersecting, prismatic 3 | as above, joint 3 prismatic | Stanford arm |
//! | planar | every axis along world z; task rows x, y (+ rz, + z) | planar 2R/3R, SCARA |
//! | position | three joints, task rows x, y, z: R R R with h1 ∩ h2 or h2 ∥ h3, R R P with h1 ∩ h2, R P P, P P R, P P P | elbow, spherical, cylindrical, Cartesian arms |
//! | Cartesian with yaw | four joints, task rows x, y, z, rz: three prismatic (independent at every yaw) and one revolute about world z, in any order | gantry with a rotary tool axis |
//! | pitch and roll | four or five revolute joints, h2 ∥ h3 ∥ h4, h1 ∦ h2; with five, h5 ∦ h2 and the tool point on axis 5: position first, the approach in the arm's plane, the roll | OpenManipulator-X (4), WidowX 250, youBot (5) |
//!
//! and, where none of those fits either way, the families whose first step is a quartic
//! (SP5, SP6 — every branch checked against `fk`):
//!
//! | family | condition | |
//! |---|---|---|
//! | spherical wrist | h4, h5, h6 meet; axes 1–3 in no special position | SP5 for (q1, q2, q3) |
//! | three parallel | h2 ∥ h3 ∥ h4, h5 and h6 not meeting | SP6 for (q1, q5) |
//!
//! and, where none of those fits either way and every joint is revolute, the **general 6R**
//! (`kinegen::ik::families::general_6r`: Raghavan and Roth's elimination, solved at run
//! time as an eigenproblem on the geometry's numbers — the Jaco, the CRX-10iA/L, the Gen3).
//!
//! Every 6-joint family is also matched on the chain **read from the tool to the base**
//! (joints 6, 5, …, 1): a spherical *shoulder* (axes 1, 2, 3 meet) is the spherical wrist
//! of the reversed chain, three parallel axes at the wrist are three parallel axes at its
//! base. The relations tested (parallel, meeting, perpendicular) do not depend on the
//! direction, so the reversed match is the same exact test on the labels reversed; the
//! runtime solves the inverted pose on the inverted geometry
//! (`kinegen::ik::reversed`) and maps the joints back.
//!
//! A 7-joint arm is solved with one joint left free (locked at a run-time value,
//! `ik_with(pose, q_free)`). Every joint is tried; the one used is the user's choice
//! (`ik_free`), else by default the last joint, then the first — locking either keeps the
//! other six's geometry the same for every locked value (it only turns the tool, or the
//! base), so the family cannot degenerate at particular locked values — else the first of
//! joints 3, 4, 5, 2, 6 whose locking leaves a family (joint 3 first: for an S-R-S arm it
//! keeps the shoulder's first two axes meeting and the wrist spherical). Relations across
//! the locked joint are tested with its angle left symbolic, so they hold for every value.

use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::ik::axes::Axes;
use crate::kinematics::ik::fewer::{cartesian_yaw, pitch_roll, planar, position};
use crate::kinematics::ik::plan::{finish, Match};
use crate::model::robot::{JointKind, TaskRow};

pub use crate::kinematics::ik::plan::{Family, IkPlan, Position};

/// Why a chain gets no closed form without anything being wrong with it: no family is
/// defined for its number of joints (only 4- to 6-joint arms, 7-joint arms with a locked
/// joint, and arms with task rows are tried). No note is given for it.
pub const OUT_OF_DOMAIN: &str = "no family is defined for this number of joints";

/// The plan for `chain`, or why there is none (each family's first broken condition,
/// naming the axes; [`OUT_OF_DOMAIN`] when no family applies to it at all). `free`: the
/// joint (0-based) a 7-joint arm's closed form leaves free, when the user chose it.
pub fn plan(chain: &Chain, max_terms: usize, free: Option<usize>) -> Result<IkPlan, String> {
    let n = chain.dof();
    let kinds: Vec<JointKind> = chain.kinds().collect();
    if let Some(k) = free {
        if n != 7 || k >= n {
            return Err(format!(
                "`ik_free` names joint {}, but only a 7-joint arm leaves a joint free ({n} joints)",
                k + 1
            ));
        }
    }
    let full = chain.task.as_ref().is_none_or(|t| t.len() == 6);
    if !full {
        let on_plane = planar(chain, max_terms, &kinds);
        let mut rows = chain.task.clone().unwrap_or_default();
        rows.sort();
        if on_plane.is_err() && n == 3 && rows == [TaskRow::X, TaskRow::Y, TaskRow::Z] {
            return position(chain, max_terms, &kinds)
                .map_err(|e| format!("{}; {e}", on_plane.err().unwrap_or_default()));
        }
        let yaw_rows = [TaskRow::X, TaskRow::Y, TaskRow::Z, TaskRow::Rz];
        if on_plane.is_err() && n == 4 && rows == yaw_rows {
            return cartesian_yaw(chain, max_terms, &kinds)
                .map_err(|e| format!("{}; {e}", on_plane.err().unwrap_or_default()));
        }
        return on_plane;
    }
    match n {
        6 => {
            let sym = SymbolicChain::at_zero(chain, max_terms, None);
            let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
            let labels: Vec<usize> = (0..6).collect();
            either_way(&axes, &kinds, &labels).map(|m| finish(m, None, Vec::new(), None))
        }
        4 | 5 => pitch_roll(chain, max_terms, &kinds).map_err(|e| {
            match task_that_solves(chain, max_terms, free) {
                Some(rows) => {
                    let rows: Vec<&str> = rows.iter().map(|r| r.name()).collect();
                    format!(
                        "{e}; declared task rows [{}] make it solvable (the `task` key; \
                         `--task {}` for a URDF on the command line)",
                        rows.join(", "),
                        rows.join(",")
                    )
                }
                None => e,
            }
        }),
        7 => seven(chain, max_terms, &kinds, free),
        _ => Err(OUT_OF_DOMAIN.into()),
    }
}

/// The task rows, one per joint, that give a chain without declared rows (or with all
/// six) a closed form (a SCARA: its axes all along z, it solves x, y, z and rz, never a
/// tilt), if any: the rows the planar family solves, else the tool point (3 joints), else
/// the point and yaw.
fn task_that_solves(chain: &Chain, max_terms: usize, free: Option<usize>) -> Option<Vec<TaskRow>> {
    // Declared rows other than all six are the user's choice, not to second-guess.
    if chain.task.as_ref().is_some_and(|t| t.len() != 6) {
        return None;
    }
    let kinds: Vec<JointKind> = chain.kinds().collect();
    let revolute = kinds.iter().filter(|k| **k == JointKind::Revolute).count();
    let mut planar = vec![TaskRow::X, TaskRow::Y];
    if revolute == 3 {
        planar.push(TaskRow::Rz);
    }
    if kinds.len() - revolute == 1 {
        planar.push(TaskRow::Z);
    }
    planar.sort();
    let candidates = [
        planar,
        vec![TaskRow::X, TaskRow::Y, TaskRow::Z],
        vec![TaskRow::X, TaskRow::Y, TaskRow::Z, TaskRow::Rz],
    ];
    candidates
        .into_iter()
        .filter(|rows| rows.len() == chain.dof())
        .find(|rows| {
            let mut c = chain.clone();
            c.task = Some(rows.clone());
            plan(&c, max_terms, free).is_ok()
        })
}

/// The 6-joint families on `labels`: those of quadratics read from the base, else from the
/// tool (the labels reversed; the relations tested do not depend on the direction), else
/// the quartic ones the same way.
fn either_way(axes: &Axes, kinds: &[JointKind], labels: &[usize]) -> Result<Match, String> {
    let quadratic = match one_tier(axes, kinds, labels, six) {
        Ok(m) => return Ok(m),
        Err(e) => e,
    };
    let quartic = match one_tier(axes, kinds, labels, six_quartic) {
        Ok(m) => return Ok(m),
        Err(e) => e,
    };
    if labels.iter().any(|&i| kinds[i] != JointKind::Revolute) {
        return Err(format!(
            "{quadratic}; quartic families: {quartic}; general 6R: a joint is prismatic"
        ));
    }
    let j = |i: usize| labels[i] + 1;
    let mut steps = vec![format!(
        "no family of subproblems fits, read either way (quadratics: {quadratic}; quartic families: {quartic}): the general 6R, whose elimination runs on the geometry's numbers at run time"
    )];
    steps.extend(steps_general(j));
    Ok(Match {
        family: Family::General6r,
        steps,
        half_turn: false,
        reversed: false,
    })
}

/// What [`six`] and [`six_quartic`] return for some labels.
type Six = fn(&Axes, &[JointKind], &[usize]) -> Result<(Family, Vec<String>, bool), String>;

/// The families of `six` on `labels`, read from the base, else from the tool.
fn one_tier(axes: &Axes, kinds: &[JointKind], labels: &[usize], six: Six) -> Result<Match, String> {
    let forward = match six(axes, kinds, labels) {
        Ok((family, steps, half_turn)) => {
            return Ok(Match {
                family,
                steps,
                half_turn,
                reversed: false,
            })
        }
        Err(e) => e,
    };
    let back: Vec<usize> = labels.iter().rev().copied().collect();
    match six(axes, kinds, &back) {
        Ok((family, steps, half_turn)) => {
            let names: Vec<String> = back.iter().map(|i| (i + 1).to_string()).collect();
            let mut all = vec![format!(
                "read from the tool: the chain inverted — joints {} in that order, target T⁻¹ = (R06ᵀ, −R06ᵀ p0T), \
                 axes and points seen from the tool at q = 0 (derived at expansion time: `ik_geometry_reversed`) — is the \
                 family below; its joint values are the robot's",
                names.join(", ")
            )];
            all.extend(steps);
            Ok(Match {
                family,
                steps: all,
                half_turn,
                reversed: true,
            })
        }
        Err(e) => Err(format!("{forward}; read from the tool: {e}")),
    }
}

/// The 6-joint families for axes `labels` (the robot's joint indices, 0-based) of `axes`.
fn six(
    axes: &Axes,
    kinds: &[JointKind],
    labels: &[usize],
) -> Result<(Family, Vec<String>, bool), String> {
    let j = |i: usize| labels[i] + 1;
    let with_pair =
        |family: Family, steps: Vec<String>, a: usize| with_pair(axes, labels, family, steps, a);
    let all_revolute = labels.iter().all(|&i| kinds[i] == JointKind::Revolute);
    let mut why = Vec::new();
    // Three parallel, two intersecting.
    let c = if !all_revolute {
        Err("a joint is prismatic".to_string())
    } else if !axes.parallel(labels[1], labels[2]) || !axes.parallel(labels[2], labels[3]) {
        Err(format!(
            "axes {}, {}, {} are not parallel",
            j(1),
            j(2),
            j(3)
        ))
    } else if !axes.intersect(labels[4], labels[5]) {
        Err(format!("axes {} and {} do not meet", j(4), j(5)))
    } else if axes.parallel(labels[0], labels[1]) {
        Err(format!("axis {} is parallel to axis {}", j(0), j(1)))
    } else {
        Ok(())
    };
    match c {
        Ok(()) => {
            return Ok(with_pair(
                Family::ThreeParallelTwoIntersecting,
                steps_ur(j),
                1,
            ))
        }
        Err(e) => why.push(format!("h2 ∥ h3 ∥ h4, h5 ∩ h6: {e}")),
    }
    // The spherical-wrist families.
    let wrist = axes.concurrent(labels[3], labels[4], labels[5]);
    let wrist_why = format!("axes {}, {}, {} do not meet in one point", j(3), j(4), j(5));
    let arm_revolute = labels[..2].iter().all(|&i| kinds[i] == JointKind::Revolute)
        && labels[3..].iter().all(|&i| kinds[i] == JointKind::Revolute);
    let third = kinds[labels[2]];
    if !arm_revolute {
        why.push("spherical wrist: joints 1, 2, 4, 5, 6 must be revolute".into());
    } else if !wrist {
        why.push(format!("spherical wrist: {wrist_why}"));
    } else if third == JointKind::Revolute
        && axes.parallel(labels[1], labels[2])
        && !axes.parallel(labels[0], labels[1])
    {
        return Ok(with_pair(
            Family::SphericalTwoParallel,
            steps_spherical_parallel(j),
            3,
        ));
    } else if axes.intersect(labels[0], labels[1]) {
        return Ok(match third {
            JointKind::Revolute => with_pair(
                Family::SphericalTwoIntersecting,
                steps_spherical_intersecting(j, false),
                3,
            ),
            JointKind::Prismatic => with_pair(
                Family::SphericalTwoIntersectingPrismatic,
                steps_spherical_intersecting(j, true),
                3,
            ),
        });
    } else {
        why.push(format!(
            "spherical wrist: neither h{} ∥ h{} (with h{} ∦ h{}) nor h{} ∩ h{}",
            j(1),
            j(2),
            j(0),
            j(1),
            j(0),
            j(1)
        ));
    }
    Err(why.join("; "))
}

/// `family` with its steps and whether its wrist is orthogonal about `a` (the axis
/// turning before h5: `a ⟂ h5 ⟂ h6`, decided exactly), the half-turn step added if so.
fn with_pair(
    axes: &Axes,
    labels: &[usize],
    family: Family,
    mut steps: Vec<String>,
    a: usize,
) -> (Family, Vec<String>, bool) {
    let j = |i: usize| labels[i] + 1;
    let half = axes.perpendicular(labels[a], labels[4]) && axes.perpendicular(labels[4], labels[5]);
    if half {
        let angle = match family {
            Family::ThreeParallelTwoIntersecting => "θ".to_string(),
            _ => format!("q{}", j(a)),
        };
        steps.push(format!(
            "the other root of q{e}: {angle} + π and q{f} + π with it, no subproblem — h{d} ⟂ h{e} ⟂ h{f} (an orthogonal wrist, decided exactly)",
            d = j(a),
            e = j(4),
            f = j(5)
        ));
    }
    (family, steps, half)
}

/// The 6-joint families whose first step is a quartic, for axes `labels` of `axes`: tried
/// where no family of quadratics ([`six`]) fits either way.
fn six_quartic(
    axes: &Axes,
    kinds: &[JointKind],
    labels: &[usize],
) -> Result<(Family, Vec<String>, bool), String> {
    let j = |i: usize| labels[i] + 1;
    let a = |i: usize| labels[i];
    if labels.iter().any(|&i| kinds[i] != JointKind::Revolute) {
        return Err("a joint is prismatic".into());
    }
    let mut why = Vec::new();
    // SP5's two equations in (q1, q3) — along h2 and the length — have coefficient
    // matrices (one per angle) that are singular for every pose when h1 ∥ h2 (or h1 ∩ h2)
    // and when h2 ∥ h3 (or h2 ∩ h3); with both, the angles are not found this way.
    if !axes.concurrent(a(3), a(4), a(5)) {
        why.push(format!(
            "spherical wrist: axes {}, {}, {} do not meet in one point",
            j(3),
            j(4),
            j(5)
        ));
    } else if axes.parallel(a(0), a(1)) && (axes.parallel(a(1), a(2)) || axes.intersect(a(1), a(2)))
    {
        why.push(format!(
            "spherical wrist: axes {} and {} are parallel and axes {} and {} parallel or meeting (SP5 does not determine q{} and q{})",
            j(0), j(1), j(1), j(2), j(0), j(2)
        ));
    } else {
        return Ok(with_pair(
            axes,
            labels,
            Family::Spherical,
            steps_spherical(j),
            3,
        ));
    }
    // SP6 on the components along h2: its matrix in q5 is singular when h5 ∥ h2, h5 ∥ h6
    // or h5 ∩ h6 (the UR family), its matrix in q1 when h1 ∥ h2.
    let c = if !axes.parallel(a(1), a(2)) || !axes.parallel(a(2), a(3)) {
        Err(format!(
            "axes {}, {}, {} are not parallel",
            j(1),
            j(2),
            j(3)
        ))
    } else if axes.parallel(a(0), a(1)) {
        Err(format!("axis {} is parallel to axis {}", j(0), j(1)))
    } else if axes.parallel(a(4), a(1)) {
        Err(format!("axis {} is parallel to axis {}", j(4), j(1)))
    } else if axes.parallel(a(4), a(5)) || axes.intersect(a(4), a(5)) {
        Err(format!("axes {} and {} are parallel or meet", j(4), j(5)))
    } else {
        Ok(())
    };
    match c {
        Ok(()) => Ok((Family::ThreeParallel, steps_three_parallel(j), false)),
        Err(e) => {
            why.push(format!("three parallel: {e}"));
            Err(why.join("; "))
        }
    }
}

/// The order in which a 7-joint arm's joints are tried as the free one by default (0-based):
/// the last and the first (locking either leaves the other six's geometry the same for every
/// locked value), then joint 3 (an S-R-S arm's usual redundancy parameter), 4, 5, 2, 6.
pub const FREE_JOINT_ORDER: [usize; 7] = [6, 0, 2, 3, 4, 1, 5];

/// A 7-joint arm with one joint locked: every joint tried, the user's `free` or the first
/// of [`FREE_JOINT_ORDER`] that leaves a family used.
fn seven(
    chain: &Chain,
    max_terms: usize,
    kinds: &[JointKind],
    free: Option<usize>,
) -> Result<IkPlan, String> {
    let tried: Vec<(usize, Result<Match, String>)> = (0..7)
        .map(|k| {
            let sym = SymbolicChain::at_zero(chain, max_terms, Some(k));
            let labels: Vec<usize> = (0..7).filter(|&i| i != k).collect();
            let m = match Axes::of(&sym) {
                None => Err("over the term budget".to_string()),
                Some(axes) => either_way(&axes, kinds, &labels).map_err(|e| {
                    let rest: Vec<String> = labels.iter().map(|i| (i + 1).to_string()).collect();
                    format!("family joints 1–6 = joints {}: {e}", rest.join(", "))
                }),
            };
            (k, m)
        })
        .collect();
    let lockable: Vec<usize> = tried
        .iter()
        .filter(|(_, m)| m.is_ok())
        .map(|(k, _)| *k)
        .collect();
    let list = |ks: &[usize]| {
        let v: Vec<String> = ks.iter().map(|k| (k + 1).to_string()).collect();
        v.join(", ")
    };
    let tier = |i: usize| tried[i].1.as_ref().map_or(u8::MAX, |m| m.family.tier());
    let others = |k: usize| {
        let rest = |t: u8| -> Vec<usize> {
            lockable
                .iter()
                .copied()
                .filter(|&i| i != k && tier(i) == t)
                .collect()
        };
        let joints = |v: &[usize]| if v.len() == 1 { "joint" } else { "joints" };
        let mut parts = Vec::new();
        for (t, how) in [
            (0, " would also do"),
            (1, " with a quartic family"),
            (2, " with the general 6R"),
        ] {
            let ks = rest(t);
            if !ks.is_empty() {
                parts.push(format!("{} {}{how}", joints(&ks), list(&ks)));
            }
        }
        if parts.is_empty() {
            String::new()
        } else {
            format!("; {} (`ik_free`)", parts.join(", "))
        }
    };
    let chosen = match free {
        Some(k) => match &tried[k].1 {
            Ok(_) => (
                k,
                format!(
                    "joint {} left free (locked at q_locked), as `ik_free` asks{}",
                    k + 1,
                    others(k)
                ),
            ),
            Err(e) => {
                let can = if lockable.is_empty() {
                    "no joint's locking leaves a family".to_string()
                } else {
                    format!("joints whose locking leaves a family: {}", list(&lockable))
                };
                return Err(format!("joint {} left free (`ik_free`): {e}; {can}", k + 1));
            }
        },
        None => {
            // A family of quadratics at any lock before a quartic one, a quartic one before
            // the general 6R.
            let first = |t: u8| FREE_JOINT_ORDER.iter().copied().find(|&k| tier(k) == t);
            let Some(k) = first(0).or_else(|| first(1)).or_else(|| first(2)) else {
                let why: Vec<String> = FREE_JOINT_ORDER
                    .iter()
                    .map(|&k| {
                        format!(
                            "joint {} locked ({})",
                            k + 1,
                            tried[k].1.as_ref().err().map_or("", |e| e)
                        )
                    })
                    .collect();
                return Err(why.join("; "));
            };
            let reason = match k {
                6 => "the last joint only turns the tool, so the six others' geometry is the same for every value".to_string(),
                0 => format!(
                    "the first joint only turns the base, so the six others' geometry is the same for every value (locking joint 7 leaves {})",
                    match &tried[6].1 {
                        Ok(m) if m.family.tier() == 2 => "only the general 6R".to_string(),
                        Ok(_) => "only a quartic family".to_string(),
                        Err(e) => format!("no family: {e}"),
                    }
                ),
                _ => "the first of joints 3, 4, 5, 2, 6 whose locking leaves a family; joints 7 and 1, whose locking keeps the geometry the same for every value, leave none or only a harder one".to_string(),
            };
            let reason = match tier(k) {
                1 => format!(
                    "{reason}; no joint's locking leaves a family of quadratics, so a quartic one"
                ),
                2 => format!(
                    "{reason}; no joint's locking leaves a family of subproblems, so the general 6R"
                ),
                _ => reason,
            };
            (
                k,
                format!(
                    "joint {} left free (locked at q_locked): {reason}{}",
                    k + 1,
                    others(k)
                ),
            )
        }
    };
    let (k, why) = chosen;
    let mut tried = tried;
    // `k` was chosen among the joints whose locking matched.
    let m = tried.swap_remove(k).1?;
    let mut plan = finish(m, Some(k), lockable, Some(why));
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    if let Some(axes) = Axes::of(&sym) {
        if kinds.iter().all(|&k| k == JointKind::Revolute) && srs(&axes) {
            plan.arm_angle = Some(steps_arm_angle());
        }
    }
    Ok(plan)
}

/// An S-R-S arm whose shoulder and wrist are orthogonal, decided exactly at `q = 0`:
/// axes 1, 2, 3 meet, axes 5, 6, 7 meet, `h1 ∥ h3 ⟂ h2` and `h5 ∥ h7 ⟂ h6` (the KUKA
/// iiwa). Its arm angle's intervals within the limits are then exact
/// (`kinegen::ik::families::arm_angle_intervals`).
fn srs(axes: &Axes) -> bool {
    axes.concurrent(0, 1, 2)
        && axes.concurrent(4, 5, 6)
        && axes.parallel(0, 2)
        && axes.perpendicular(0, 1)
        && axes.parallel(4, 6)
        && axes.perpendicular(4, 5)
}

fn steps_arm_angle() -> Vec<String> {
    vec![
        "S where axes 1, 2, 3 meet; W0 where axes 5, 6, 7 meet; E0 the point of axis 4 nearest S".into(),
        "wrist centre W = p0T − R07 (pT − W0); u = (W − S)/‖W − S‖".into(),
        "q4 — SP3: ‖(E0 − S) + rot(h4, q4) (W0 − E0)‖ = ‖W − S‖ (two roots)".into(),
        "R03 = rot(u, ψ) R03(0): R03(0) takes the zero configuration's shoulder–wrist vector onto u and the elbow's offset from it onto e1, the part of h1 orthogonal to u (ψ = 0: the elbow in the plane of the shoulder–wrist line and axis 1, on h1's side; singular when u ∥ h1)".into(),
        "q2 — SP4, q1 and q3 — SP1 on R03 (the shoulder as a spherical wrist; the other root of q2 by half turns)".into(),
        "q6 — SP4, q5 and q7 — SP1 on R47 = (R03 R4)ᵀ R07".into(),
        "each joint's sine and cosine are a sin ψ + b cos ψ + c up to a positive factor: a limit is met where such a sinusoid vanishes (arm_angle_intervals)".into(),
    ]
}

fn steps_ur(j: impl Fn(usize) -> usize) -> Vec<String> {
    vec![
        format!("p16 = p0T − R06 p6T − p1, with p6T from the point where axes {} and {} meet", j(4), j(5)),
        format!("q{} — SP4: h{b}ᵀ rot(−h{a}, q{a}) p16 = h{b}ᵀ (p12 + p23 + p34 + p45) (two roots)", j(0), a = j(0), b = j(1)),
        format!("q{} — SP4: h{}ᵀ rot(h{e}, q{e}) h{} = h{}ᵀ R1ᵀ R06 h{} (two roots)", j(4), j(1), j(5), j(1), j(5), e = j(4)),
        format!("θ = q{} ± q{} ± q{} — SP1: rot(h{}, θ) R{} h{} = R1ᵀ R06 h{} (singular when R{} h{} ∥ h{}: q{} is then free)", j(1), j(2), j(3), j(1), j(4), j(5), j(5), j(4), j(5), j(1), j(5)),
        format!("q{} — SP3: ‖p23 + rot(h{}, q{}) p34‖ = ‖R1ᵀ p16 − p12 − rot(h{}, θ) p45‖ (two roots)", j(2), j(2), j(2), j(1)),
        format!("q{} — SP1; q{} from θ", j(1), j(3)),
        format!("q{} — SP1: rot(h{}, q{}) h{} = (R1 ⋯ R5)ᵀ R06 h{}", j(5), j(5), j(5), j(4), j(4)),
    ]
}

fn steps_spherical(j: impl Fn(usize) -> usize) -> Vec<String> {
    let mut s = vec![
        wrist_centre_step(&j),
        format!(
            "(q{a}, q{c}) — SP6 on the two equations SP5 leaves: h{b}ᵀ rot(−h{a}, q{a}) p16 − h{b}ᵀ rot(h{c}, q{c}) p34 = h{b}ᵀ (p12 + p23) \
             and p12ᵀ rot(−h{a}, q{a}) p16 + p23ᵀ rot(h{c}, q{c}) p34 = (‖p16‖² + ‖p12‖² − ‖p23‖² − ‖p34‖²) / 2 \
             — a quartic in q{c} (or q{a}), up to four roots, each checked against fk",
            a = j(0),
            b = j(1),
            c = j(2)
        ),
        shoulder_sp1_step(&j),
    ];
    s.extend(wrist_steps(&j));
    s
}

/// The wrist centre and its offset from joint 1's point.
fn wrist_centre_step(j: &impl Fn(usize) -> usize) -> String {
    format!(
        "wrist centre w = p0T − R06 p6T (axes {}, {}, {} meet there); p16 = w − p1",
        j(3),
        j(4),
        j(5)
    )
}

/// q2 turning the arm onto the wrist centre, q1 and q3 known.
fn shoulder_sp1_step(j: &impl Fn(usize) -> usize) -> String {
    format!(
        "q{b} — SP1: rot(h{b}, q{b}) (p23 + R{c} p34) = rot(−h{a}, q{a}) p16 − p12",
        a = j(0),
        b = j(1),
        c = j(2)
    )
}

/// The general 6R's derivation (`kinegen::ik::families::general_6r`), for axes numbered
/// by `j`.
fn steps_general(j: impl Fn(usize) -> usize) -> Vec<String> {
    let (a, b, c, d, e, f) = (j(0), j(1), j(2), j(3), j(4), j(5));
    vec![
        format!(
            "the loop e^(ξ{a} q{a}) ⋯ e^(ξ{f} q{f}) M T⁻¹ = I; a joint k's point and direction (p_k, h_k) do not move with q_k: carried round the loop from k, split after two joints (three on the other side) — Raghavan and Roth's form, e^(ξ{c} q{c}) e^(ξ{d} q{d}) e^(ξ{e} q{e}) (p{f}, h{f}) = e^(−ξ{b} q{b}) e^(−ξ{a} q{a}) (pT, lT), first; twelve such forms, the first well conditioned at a reference pose used (read once per arm; another where a pose makes it ill conditioned)"
        ),
        "both sides' 14 quantities p, l, p·p, p·l, p × l, (p·p) l − 2 (p·l) p: linear in the nine products of the three-joint side's inner two joints' {1, cos, sin}, with coefficients linear in the outer joint's {1, cos, sin}, and linear in the nine products of the two-joint side's — coefficients read off the geometry on a grid of thirds of a turn (exact three-point Fourier sums)"
            .to_string(),
        "the two-joint side's eight products eliminated (Householder reflections of their 14 × 8 matrix): six equations in three joints; with x = tan(q/2) (offset) and the six multiplied by x of the second, twelve equations linear in twelve monomials: (A x² + B x + C) v = 0 in the outer joint's x"
            .to_string(),
        "x — the real eigenvalues of the 24 × 24 companion matrix (of the better-conditioned end, x or 1/x): its eight at x = ±i (the determinant's factor (1 + x²)⁴) taken out by an orthogonal similarity read off the six equations at x = i and checked, then Francis's double-shift QR on the 16 × 16 matrix left (Hessenberg form, eigenvalues only, bounded sweeps): at most 16 real solutions"
            .to_string(),
        "the three-joint side's inner joints from the null vector v (ratios of neighbouring monomials); the two-joint side's from the triangular factor of the elimination; the carried joint by SP1 on the rotation"
            .to_string(),
        "each branch polished by Newton steps on fk where it misses the pose by more than rounding, and checked there; branches the rounding made twice merged"
            .to_string(),
    ]
}

fn steps_three_parallel(j: impl Fn(usize) -> usize) -> Vec<String> {
    vec![
        format!("p16 = p0T − R06 p6T − p1, with p6T from joint {}'s point", j(5)),
        format!(
            "(q{a}, q{e}) — SP6: h{b}ᵀ rot(−h{a}, q{a}) p16 − h{b}ᵀ rot(h{e}, q{e}) p56 = h{b}ᵀ (p12 + p23 + p34 + p45) \
             and h{b}ᵀ rot(−h{a}, q{a}) R06 h{f} = h{b}ᵀ rot(h{e}, q{e}) h{f} (turns about h{b} ∥ h{c} ∥ h{d} keep both) \
             — a quartic, up to four roots, each checked against fk",
            a = j(0),
            b = j(1),
            c = j(2),
            d = j(3),
            e = j(4),
            f = j(5)
        ),
        format!(
            "q{f} — SP1: rot(h{f}, q{f}) R06ᵀ R1 h{b} = R{e}ᵀ h{b} (singular when R{e}ᵀ h{b} ∥ h{f}: q{f} is then free)",
            b = j(1),
            e = j(4),
            f = j(5)
        ),
        format!(
            "θ = q{} ± q{} ± q{} — SP1: rot(h{b}, θ) x = R1ᵀ R06 R{f}ᵀ R{e}ᵀ x for x ⟂ h{b}",
            j(1),
            j(2),
            j(3),
            b = j(1),
            e = j(4),
            f = j(5)
        ),
        format!(
            "q{c} — SP3: ‖p23 + rot(h{c}, q{c}) p34‖ = ‖R1ᵀ p16 − p12 − rot(h{b}, θ) (p45 + R{e} p56)‖ (two roots)",
            b = j(1),
            c = j(2),
            e = j(4)
        ),
        format!("q{} — SP1; q{} from θ", j(1), j(3)),
    ]
}

fn steps_spherical_parallel(j: impl Fn(usize) -> usize) -> Vec<String> {
    let mut s = vec![
        wrist_centre_step(&j),
        format!(
            "q{a} — SP4: h{b}ᵀ rot(−h{a}, q{a}) p16 = h{b}ᵀ (p12 + p23 + p34) (two roots)",
            a = j(0),
            b = j(1)
        ),
        format!(
            "q{c} — SP3: ‖p23 + rot(h{c}, q{c}) p34‖ = ‖rot(−h{a}, q{a}) p16 − p12‖ (two roots)",
            a = j(0),
            c = j(2)
        ),
        shoulder_sp1_step(&j),
    ];
    s.extend(wrist_steps(&j));
    s
}

fn steps_spherical_intersecting(j: impl Fn(usize) -> usize, prismatic: bool) -> Vec<String> {
    let mut s = vec![format!(
        "wrist centre w = p0T − R06 p6T (axes {}, {}, {} meet there); p16 = w − c12 (axes {} and {} meet at c12)",
        j(3),
        j(4),
        j(5),
        j(0),
        j(1)
    )];
    if prismatic {
        s.push(format!(
            "q{c} — ‖u + q{c} h{c}‖ = ‖p16‖ with u = p23 + p34 (a quadratic, two roots)",
            c = j(2)
        ));
    } else {
        s.push(format!(
            "q{c} — SP3: ‖p23 + rot(h{c}, q{c}) p34‖ = ‖p16‖ (two roots)",
            c = j(2)
        ));
    }
    s.push(format!(
        "(q{a}, q{b}) — SP2: rot(−h{a}, q{a}) p16 = rot(h{b}, q{b}) (arm vector) (two pairs; q{a} free when w is on axis {a})",
        a = j(0),
        b = j(1)
    ));
    s.extend(wrist_steps(&j));
    s
}

fn wrist_steps(j: &impl Fn(usize) -> usize) -> Vec<String> {
    vec![
        format!("R36 = (R{} R{} R{})ᵀ R06", j(0), j(1), j(2)),
        format!("q{e} — SP4: h{d}ᵀ rot(h{e}, q{e}) h{f} = h{d}ᵀ R36 h{f} (two roots)", d = j(3), e = j(4), f = j(5)),
        format!("q{d} — SP1: rot(h{d}, q{d}) R{e} h{f} = R36 h{f} (singular when R{e} h{f} ∥ h{d}: q{d} is then free, q{f} from the whole rotation)", d = j(3), e = j(4), f = j(5)),
        format!("q{f} — SP1: rot(h{f}, q{f})ᵀ R{e}ᵀ h{d} = R36ᵀ h{d}", d = j(3), e = j(4), f = j(5)),
    ]
}
