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
use crate::model::robot::{JointKind, TaskRow};

/// A closed-form family.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Family {
    /// h2 ∥ h3 ∥ h4, h5 ∩ h6.
    ThreeParallelTwoIntersecting,
    /// Spherical wrist, h2 ∥ h3.
    SphericalTwoParallel,
    /// Spherical wrist, h1 ∩ h2.
    SphericalTwoIntersecting,
    /// Spherical wrist, h1 ∩ h2, joint 3 prismatic.
    SphericalTwoIntersectingPrismatic,
    /// All axes along world z: revolute joints (2 or 3, 0-based) and at most one
    /// prismatic joint, solving task rows x, y (rz with 3 revolute joints, z with the
    /// prismatic one).
    Planar {
        /// Revolute joints, in order.
        revolute: Vec<usize>,
        /// The prismatic joint, if any.
        prismatic: Option<usize>,
    },
    /// Three joints placing the tool point (task rows x, y, z).
    Position(Position),
    /// Three prismatic joints and one revolute joint about world z, in any order (task
    /// rows x, y, z, rz): the yaw, then the slides from a linear system
    /// (`kinegen::ik::families::cartesian_yaw`).
    CartesianYaw {
        /// The revolute joint (0-based).
        revolute: usize,
    },
    /// Four or five revolute joints, h2 ∥ h3 ∥ h4 after h1 (h1 ∦ h2); with five, the tool
    /// point on axis 5 (h5 ∦ h2): the position, the approach in the arm's plane and the
    /// roll (`kinegen::ik::families::pitch_roll`).
    PitchRoll {
        /// Five joints (a roll at the tool), else four.
        roll: bool,
    },
    /// Spherical wrist, the first three axes in no special position: SP5 (a quartic).
    Spherical,
    /// h2 ∥ h3 ∥ h4, h5 and h6 not meeting: SP6 (a quartic).
    ThreeParallel,
}

/// The cases of [`Family::Position`] (`kinegen::ik::families::position_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Position {
    /// R R R, h1 ∩ h2: q3 by SP3, (q1, q2) by SP2.
    Intersecting,
    /// R R R, h2 ∥ h3, h1 ∦ h2: q1 by SP4, q3 by SP3, q2 by SP1.
    Parallel,
    /// R R P, h1 ∩ h2: q3 from a quadratic, (q1, q2) by SP2.
    IntersectingPrismatic,
    /// One revolute joint, first (R P P, the cylindrical arm) or last (P P R), the
    /// prismatic axes not parallel and not both orthogonal to the revolute one.
    OneRevolute {
        /// The revolute joint is joint 1 (else joint 3).
        revolute_first: bool,
    },
    /// P P P, the axes independent.
    Cartesian,
}

/// How a robot's IK is generated.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IkPlan {
    /// The family.
    pub family: Family,
    /// The joint locked (0-based) for a 7-joint arm.
    pub locked: Option<usize>,
    /// The family matches the chain read from the tool to the base: the runtime solves
    /// the inverted pose on the inverted geometry and reverses the joints back.
    pub reversed: bool,
    /// A 7-joint arm: every joint (0-based) whose locking leaves a family, in order.
    pub lockable: Vec<usize>,
    /// An S-R-S arm with an orthogonal shoulder and wrist (the iiwa): the derivation of
    /// its solutions by arm angle (`ik_arm_angle`, `arm_angle_intervals`), else `None`.
    pub arm_angle: Option<Vec<String>>,
    /// One-line name for `IK_FAMILY`.
    pub name: String,
    /// The derivation, one line per step, with the robot's joint numbers.
    pub steps: Vec<String>,
    /// Most solutions a pose can have.
    pub max_solutions: usize,
    /// The wrist is orthogonal (`a ⟂ h5 ⟂ h6` at `q = 0`, with `a` the axis turning
    /// before h5: h4, or h2 ∥ h3 ∥ h4 for the UR family), decided exactly: the second
    /// root of q5 takes the other wrist joints from the first by half turns
    /// (`kinegen::ik::families::WristPair::HalfTurn`).
    pub wrist_half_turn: bool,
}

impl Family {
    /// The runtime solver in `kinegen::ik::families`.
    pub fn solver(&self) -> &'static str {
        match self {
            Family::ThreeParallelTwoIntersecting => "three_parallel_two_intersecting",
            Family::SphericalTwoParallel => "spherical_two_parallel",
            Family::SphericalTwoIntersecting => "spherical_two_intersecting",
            Family::SphericalTwoIntersectingPrismatic => "spherical_two_intersecting_prismatic",
            Family::Planar { .. } => "planar",
            Family::Position(Position::Intersecting) => "position_intersecting",
            Family::Position(Position::Parallel) => "position_parallel",
            Family::Position(Position::IntersectingPrismatic) => "position_intersecting_prismatic",
            Family::Position(Position::OneRevolute { .. }) => "position_one_revolute",
            Family::Position(Position::Cartesian) => "position_cartesian",
            Family::PitchRoll { .. } => "pitch_roll",
            Family::CartesianYaw { .. } => "cartesian_yaw",
            Family::Spherical => "spherical",
            Family::ThreeParallel => "three_parallel",
        }
    }

    /// The family's first step is a quartic (SP5 or SP6): chosen only where no family of
    /// quadratics fits, either way round or with any joint locked.
    pub fn quartic(&self) -> bool {
        matches!(self, Family::Spherical | Family::ThreeParallel)
    }

    fn title(&self) -> &'static str {
        match self {
            Family::ThreeParallelTwoIntersecting => "three parallel, two intersecting",
            Family::SphericalTwoParallel => "spherical wrist, two parallel",
            Family::SphericalTwoIntersecting => "spherical wrist, two intersecting",
            Family::SphericalTwoIntersectingPrismatic => {
                "spherical wrist, two intersecting, prismatic joint 3"
            }
            Family::Planar { .. } => "planar",
            Family::Position(Position::Intersecting) => "position, h1 ∩ h2",
            Family::Position(Position::Parallel) => "position, h2 ∥ h3",
            Family::Position(Position::IntersectingPrismatic) => {
                "position, h1 ∩ h2, prismatic joint 3"
            }
            Family::Position(Position::OneRevolute {
                revolute_first: true,
            }) => "position, cylindrical (R P P)",
            Family::Position(Position::OneRevolute {
                revolute_first: false,
            }) => "position, P P R",
            Family::Position(Position::Cartesian) => "position, Cartesian (P P P)",
            Family::CartesianYaw { .. } => "position and yaw, Cartesian with a turn about z",
            Family::PitchRoll { roll: false } => "position and pitch, h2 ∥ h3 ∥ h4 (4 joints)",
            Family::PitchRoll { roll: true } => {
                "position, pitch and roll, h2 ∥ h3 ∥ h4, tool on axis 5 (5 joints)"
            }
            Family::Spherical => "spherical wrist, general arm (SP5)",
            Family::ThreeParallel => "three parallel (SP6)",
        }
    }

    /// Most solutions a pose can have.
    fn max_solutions(&self) -> usize {
        match self {
            Family::Planar { .. } => 2,
            Family::Position(Position::OneRevolute { .. }) => 2,
            Family::Position(Position::Cartesian) | Family::CartesianYaw { .. } => 1,
            Family::Position(_) | Family::PitchRoll { .. } => 4,
            _ => 8,
        }
    }
}

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
        4 | 5 => pitch_roll(chain, max_terms, &kinds),
        7 => seven(chain, max_terms, &kinds, free),
        _ => Err(OUT_OF_DOMAIN.into()),
    }
}

/// A 6-joint family matched on some labels: the family, its steps, whether the wrist is
/// orthogonal, whether the labels were read from the tool.
struct Match {
    family: Family,
    steps: Vec<String>,
    half_turn: bool,
    reversed: bool,
}

/// `why`: the line saying which joint a 7-joint arm leaves free and why.
fn finish(m: Match, locked: Option<usize>, lockable: Vec<usize>, why: Option<String>) -> IkPlan {
    let direction = if m.reversed {
        ", read from the tool"
    } else {
        ""
    };
    let name = match locked {
        Some(k) => format!("{}{direction} (joint {} locked)", m.family.title(), k + 1),
        None => format!("{}{direction}", m.family.title()),
    };
    let max_solutions = m.family.max_solutions();
    let mut steps: Vec<String> = why.into_iter().collect();
    steps.extend(m.steps);
    IkPlan {
        family: m.family,
        locked,
        reversed: m.reversed,
        lockable,
        arm_angle: None,
        name,
        steps,
        max_solutions,
        wrist_half_turn: m.half_turn,
    }
}

/// The 6-joint families on `labels`: those of quadratics read from the base, else from the
/// tool (the labels reversed; the relations tested do not depend on the direction), else
/// the quartic ones the same way.
fn either_way(axes: &Axes, kinds: &[JointKind], labels: &[usize]) -> Result<Match, String> {
    match one_tier(axes, kinds, labels, six) {
        Ok(m) => Ok(m),
        Err(quadratic) => one_tier(axes, kinds, labels, six_quartic)
            .map_err(|quartic| format!("{quadratic}; quartic families: {quartic}")),
    }
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
                 axes and points seen from the tool at q = 0 — is the family below; its joint values are the robot's",
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
    let quartic = |i: usize| tried[i].1.as_ref().is_ok_and(|m| m.family.quartic());
    let others = |k: usize| {
        let rest = |q: bool| -> Vec<usize> {
            lockable
                .iter()
                .copied()
                .filter(|&i| i != k && quartic(i) == q)
                .collect()
        };
        let joints = |v: &[usize]| if v.len() == 1 { "joint" } else { "joints" };
        let (quadratic, quartics) = (rest(false), rest(true));
        let mut parts = Vec::new();
        if !quadratic.is_empty() {
            parts.push(format!(
                "{} {} would also do",
                joints(&quadratic),
                list(&quadratic)
            ));
        }
        if !quartics.is_empty() {
            parts.push(format!(
                "{} {} with a quartic family",
                joints(&quartics),
                list(&quartics)
            ));
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
            // A family of quadratics at any lock before a quartic one.
            let fits = |k: usize, quartic: bool| {
                tried[k]
                    .1
                    .as_ref()
                    .is_ok_and(|m| m.family.quartic() == quartic)
            };
            let first =
                |quartic: bool| FREE_JOINT_ORDER.iter().copied().find(|&k| fits(k, quartic));
            let Some(k) = first(false).or_else(|| first(true)) else {
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
            let quartic = tried[k].1.as_ref().is_ok_and(|m| m.family.quartic());
            let reason = match k {
                6 => "the last joint only turns the tool, so the six others' geometry is the same for every value".to_string(),
                0 => format!(
                    "the first joint only turns the base, so the six others' geometry is the same for every value (locking joint 7 leaves {})",
                    match &tried[6].1 {
                        Ok(_) => "only a quartic family".to_string(),
                        Err(e) => format!("no family: {e}"),
                    }
                ),
                _ => "the first of joints 3, 4, 5, 2, 6 whose locking leaves a family; joints 7 and 1, whose locking keeps the geometry the same for every value, leave none".to_string(),
            };
            let reason = if quartic {
                format!(
                    "{reason}; no joint's locking leaves a family of quadratics, so a quartic one"
                )
            } else {
                reason
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

/// Planar arms solving their task rows.
fn planar(chain: &Chain, max_terms: usize, kinds: &[JointKind]) -> Result<IkPlan, String> {
    let task = chain.task.clone().unwrap_or_default();
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let z = crate::kinematics::ik::axes::unit_z();
    if let Some(i) = (0..chain.dof()).find(|&i| !axes.along(i, &z)) {
        return Err(format!("planar: axis {} is not along world z", i + 1));
    }
    let revolute: Vec<usize> = (0..chain.dof())
        .filter(|&i| kinds[i] == JointKind::Revolute)
        .collect();
    let prismatic: Vec<usize> = (0..chain.dof())
        .filter(|&i| kinds[i] == JointKind::Prismatic)
        .collect();
    let mut want = vec![TaskRow::X, TaskRow::Y];
    if revolute.len() == 3 {
        want.push(TaskRow::Rz);
    }
    if prismatic.len() == 1 {
        want.push(TaskRow::Z);
    }
    let mut have = task.clone();
    have.sort();
    want.sort();
    if !(2..=3).contains(&revolute.len()) || prismatic.len() > 1 || have != want {
        return Err(format!(
            "planar: {} revolute and {} prismatic joints along z with task rows [{}] (planar IK \
             solves x, y with 2 revolute joints, + rz with 3, + z with one prismatic joint)",
            revolute.len(),
            prismatic.len(),
            task.iter().map(|r| r.name()).collect::<Vec<_>>().join(", ")
        ));
    }
    let steps = steps_planar(&revolute, prismatic.first().copied());
    let family = Family::Planar {
        revolute,
        prismatic: prismatic.first().copied(),
    };
    let m = Match {
        family,
        steps,
        half_turn: false,
        reversed: false,
    };
    Ok(finish(m, None, Vec::new(), None))
}

/// Three joints placing the tool point (task rows x, y, z): the cases of [`Position`],
/// decided exactly at `q = 0`.
fn position(chain: &Chain, max_terms: usize, kinds: &[JointKind]) -> Result<IkPlan, String> {
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let r = |i: usize| kinds[i] == JointKind::Revolute;
    let (case, steps) = match (r(0), r(1), r(2)) {
        (true, true, third) if axes.intersect(0, 1) && !axes.parallel(0, 1) => {
            if third {
                (
                    Position::Intersecting,
                    vec![
                        "c12 where axes 1 and 2 meet; d = p − c12".to_string(),
                        "q3 — SP3: ‖(p3 − c12) + rot(h3, q3) (pT − p3)‖ = ‖d‖ (two roots)".into(),
                        "(q1, q2) — SP2: rot(−h1, q1) d = rot(h2, q2) ((p3 − c12) + R3 (pT − p3)) (two pairs; q1 free when p is on axis 1)".into(),
                    ],
                )
            } else {
                (
                    Position::IntersectingPrismatic,
                    vec![
                        "c12 where axes 1 and 2 meet; d = p − c12, u = pT − c12".to_string(),
                        "q3 — ‖u + q3 h3‖ = ‖d‖ (a quadratic, two roots)".into(),
                        "(q1, q2) — SP2: rot(−h1, q1) d = rot(h2, q2) (u + q3 h3) (two pairs; q1 free when p is on axis 1)".into(),
                    ],
                )
            }
        }
        (true, true, true) if axes.parallel(1, 2) && !axes.parallel(0, 1) => (
            Position::Parallel,
            vec![
                "q1 — SP4: h2ᵀ rot(−h1, q1) (p − p1) = h2ᵀ (pT − p1) (two roots)".to_string(),
                "q3 — SP3: ‖p23 + rot(h3, q3) p3T‖ = ‖rot(−h1, q1) (p − p1) − p12‖ (two roots)".into(),
                "q2 — SP1: rot(h2, q2) (p23 + R3 p3T) = rot(−h1, q1) (p − p1) − p12".into(),
            ],
        ),
        (first, false, last) if first != last => {
            // One revolute joint, first or last; the prismatic axes a, b.
            let (rv, [a, b]) = if first { (0, [1, 2]) } else { (2, [0, 1]) };
            if axes.parallel(a, b) {
                return Err(format!(
                    "position: the prismatic axes {} and {} are parallel",
                    a + 1,
                    b + 1
                ));
            }
            if axes.perpendicular(rv, a) && axes.perpendicular(rv, b) {
                return Err(format!(
                    "position: axis {} is orthogonal to both prismatic axes: the component of p along it is fixed",
                    rv + 1
                ));
            }
            let steps = if first {
                vec![
                    "n = h2 × h3 / ‖h2 × h3‖".to_string(),
                    "q1 — SP4: nᵀ rot(−h1, q1) (p − p1) = nᵀ (pT − p1) (two roots)".into(),
                    "(q2, q3) — q2 h2 + q3 h3 = rot(−h1, q1) (p − p1) − (pT − p1) (a 2 × 2 linear system)".into(),
                ]
            } else {
                vec![
                    "n = h1 × h2 / ‖h1 × h2‖".to_string(),
                    "q3 — SP4: nᵀ rot(h3, q3) (pT − p3) = nᵀ (p − p3) (two roots)".into(),
                    "(q1, q2) — q1 h1 + q2 h2 = (p − p3) − rot(h3, q3) (pT − p3) (a 2 × 2 linear system)".into(),
                ]
            };
            (
                Position::OneRevolute {
                    revolute_first: first,
                },
                steps,
            )
        }
        (false, false, false) => {
            if !axes.independent(0, 1, 2) {
                return Err("position: the prismatic axes are not independent".into());
            }
            (
                Position::Cartesian,
                vec!["(q1, q2, q3) — q1 h1 + q2 h2 + q3 h3 = p − pT (Cramer's rule)".to_string()],
            )
        }
        _ => {
            return Err(
                "position: none of R R R with h1 ∩ h2 or h2 ∥ h3, R R P with h1 ∩ h2, R P P, P P R, P P P"
                    .into(),
            )
        }
    };
    let m = Match {
        family: Family::Position(case),
        steps,
        half_turn: false,
        reversed: false,
    };
    Ok(finish(m, None, Vec::new(), None))
}

/// Four joints, task rows x, y, z, rz, not all along z: [`Family::CartesianYaw`], decided
/// exactly at `q = 0`.
fn cartesian_yaw(chain: &Chain, max_terms: usize, kinds: &[JointKind]) -> Result<IkPlan, String> {
    let revolute: Vec<usize> = (0..4)
        .filter(|&i| kinds[i] == JointKind::Revolute)
        .collect();
    let &[r] = revolute.as_slice() else {
        return Err(format!(
            "Cartesian with yaw: {} revolute joints (it has one, about z, and three prismatic)",
            revolute.len()
        ));
    };
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let z = crate::kinematics::ik::axes::unit_z();
    let slides: Vec<usize> = (0..4).filter(|&i| i != r).collect();
    // The yaw turns the slides after joint r: their determinant stays what it is at q = 0
    // when none comes before r, or every one after r is vertical.
    let constant =
        slides.iter().all(|&i| i > r) || slides.iter().all(|&i| i < r || axes.along(i, &z));
    let fails = [
        (
            !axes.along(r, &z),
            format!("axis {} is not along world z", r + 1),
        ),
        (
            !axes.independent(slides[0], slides[1], slides[2]),
            "the prismatic axes are not independent".into(),
        ),
        (
            !constant,
            format!(
                "a prismatic axis after joint {} is not vertical: the yaw would turn it against those before",
                r + 1
            ),
        ),
    ];
    if let Some((_, why)) = fails.iter().find(|(fail, _)| *fail) {
        return Err(format!("Cartesian with yaw: {why}"));
    }
    let names: Vec<String> = slides.iter().map(|i| format!("q{}", i + 1)).collect();
    let steps = vec![
        format!(
            "q{} — the yaw: ψ = φ − φ0 (the tool's angle about z, minus its angle at q = 0), q{} = ±ψ",
            r + 1,
            r + 1
        ),
        format!(
            "({}) — p = c + Σ qi ai with q{} known (c the tool point with the slides at 0, ai their axes): Cramer's rule",
            names.join(", "),
            r + 1
        ),
    ];
    let m = Match {
        family: Family::CartesianYaw { revolute: r },
        steps,
        half_turn: false,
        reversed: false,
    };
    Ok(finish(m, None, Vec::new(), None))
}

/// Four or five revolute joints, the whole pose: [`Family::PitchRoll`], decided exactly at
/// `q = 0`.
fn pitch_roll(chain: &Chain, max_terms: usize, kinds: &[JointKind]) -> Result<IkPlan, String> {
    let n = chain.dof();
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let roll = n == 5;
    let fails = [
        (
            kinds.iter().any(|k| *k != JointKind::Revolute),
            "a joint is prismatic".to_string(),
        ),
        (
            !(axes.parallel(1, 2) && axes.parallel(2, 3)),
            "axes 2, 3, 4 are not parallel".into(),
        ),
        (axes.parallel(0, 1), "axis 1 is parallel to axis 2".into()),
        (
            roll && axes.parallel(4, 1),
            "axis 5 is parallel to axes 2–4 (the roll would add to the pitch)".into(),
        ),
        (
            roll && !axes.tool_on(4),
            "the tool point is off axis 5 (the roll would move it)".into(),
        ),
    ];
    if let Some((_, why)) = fails.iter().find(|(fail, _)| *fail) {
        return Err(format!("pitch and roll ({n} joints): {why}"));
    }
    let v = if roll { "h5" } else { "v = h2 × h1" };
    let mut steps = vec![
        format!(
            "q1 — SP4: h2ᵀ rot(−h1, q1) (p − p1) = h2ᵀ (pT − p1) (two roots: the arm's plane; \
             joints 2–{n} keep the tool point's component along h2); with the tool point on axis 1, \
             (q1, θ) — SP2 from the approach: rot(−h1, q1) R {v} = rot(h2, θ) {v}"
        ),
        format!(
            "θ = q2 ± q3 ± q4 — SP1: rot(h2, θ) {v} = rot(−h1, q1) R {v}, R = R0T RTᵀ (the approach; \
             least squares where it leaves the arm's plane: the position comes first)"
        ),
    ];
    if roll {
        steps.push(
            "q5 — SP1: rot(h5, q5) x = rot(h2, −θ) rot(−h1, q1) R x, x = h5 × h2 (the roll)".into(),
        );
    }
    steps.extend([
        "q3 — SP3: ‖p23 + rot(h3, q3) p34‖ = ‖w‖, w = rot(−h1, q1) (p − p1) − p12 − rot(h2, θ) (pT − p4) (two roots)".to_string(),
        "q2 — SP1: rot(h2, q2) (p23 + R3 p34) = w; q4 = ±(θ − q2 ∓ q3)".into(),
    ]);
    let m = Match {
        family: Family::PitchRoll { roll },
        steps,
        half_turn: false,
        reversed: false,
    };
    Ok(finish(m, None, Vec::new(), None))
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

fn steps_planar(revolute: &[usize], prismatic: Option<usize>) -> Vec<String> {
    let r: Vec<usize> = revolute.iter().map(|i| i + 1).collect();
    let mut s = Vec::new();
    if r.len() == 3 {
        s.push(format!(
            "φ = the tool's angle about z; the point on axis {c} is p{c} = p − rot(z, φ − φ0) (pT − p{c})",
            c = r[2]
        ));
    }
    let (w, end) = match r.get(2) {
        Some(c) => (format!("p{c}"), format!("p{}{c}", r[1])),
        None => ("p".to_string(), format!("p{}T", r[1])),
    };
    s.push(format!(
        "q{b} — SP3 in the xy plane: ‖p{a}{b} + rot(h{b}, q{b}) {end}‖ = ‖{w} − p{a}‖ (elbow up / down)",
        a = r[0],
        b = r[1]
    ));
    s.push(format!("q{} — SP1", r[0]));
    if r.len() == 3 {
        s.push(format!(
            "q{} from φ = ±q{} ± q{} ± q{} + φ0",
            r[2], r[0], r[1], r[2]
        ));
    }
    if let Some(p) = prismatic {
        s.push(format!("q{} from z (it moves along z)", p + 1));
    }
    s
}
