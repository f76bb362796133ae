//! The arm families with closed-form IK from subproblems SP1–SP4 (quadratics at most) and
//! SP5/SP6 (a quartic), after IK-Geo (Elias & Wen) and EAIK (Ostermeier et al.). The engine decides at
//! expansion time, exactly, which family a robot belongs to; these functions solve a pose
//! for a [`Geometry`] that has the family's structure.
//!
//! Each takes `free`: the joint values used where the pose leaves a joint undetermined
//! (a singular configuration — UR or spherical wrist with `h4 ∥ h6`, wrist centre on
//! axis 1). `ik_near` passes the current configuration, so the answer is continuous. Each
//! pushes its candidates into the caller's `out` (empty before): the generated `ik` keeps
//! them on its stack, where `finish` reads them.
//!
//! Joint numbers in the docs are 1-based, as in the robot's tables; `h`, `p` indices are
//! 0-based.
//!
//! One file per family: `ur.rs` (h2 ∥ h3 ∥ h4, h5 ∩ h6: [`three_parallel_two_intersecting`]),
//! `spherical_two_parallel.rs` (spherical wrist, h2 ∥ h3: [`spherical_two_parallel()`]),
//! `spherical_two_intersecting.rs` (spherical wrist, h1 ∩ h2, joint 3 revolute or
//! prismatic: [`spherical_two_intersecting()`], [`spherical_two_intersecting_prismatic`]),
//! `planar.rs` (every axis along world z: [`planar()`]), `position.rs` (three joints
//! placing the tool point: [`position_intersecting`] and the other position cases),
//! `cartesian_yaw.rs` (a gantry with a turn about z, task x, y, z, rz: [`cartesian_yaw()`]),
//! `pitch_roll.rs` (four or five joints, h2 ∥ h3 ∥ h4: position, the approach in the
//! arm's plane and a roll — [`pitch_roll()`]),
//! and the two whose first step is a quartic, every branch checked against `fk`:
//! `spherical.rs` (spherical wrist after three axes in no special position, SP5:
//! [`spherical()`]) and `three_parallel.rs` (h2 ∥ h3 ∥ h4 with h5, h6 not meeting, SP6:
//! [`three_parallel()`]); the spherical wrist four of them end in is `wrist.rs`. Six
//! revolute axes in no family: `general_6r/` ([`general_6r()`], Raghavan and Roth's
//! elimination to an eigenproblem). A 7-joint S-R-S arm (the iiwa) is also solved by its arm
//! angle: `srs.rs` ([`srs_arm_angle`], [`arm_angle_intervals`]).

use super::geometry::{Geometry, Pose};
use super::solutions::Candidates;

mod cartesian_yaw;
mod general_6r;
mod pitch_roll;
mod planar;
mod position;
mod spherical;
mod spherical_two_intersecting;
mod spherical_two_parallel;
mod srs;
mod three_parallel;
mod ur;
mod wrist;

pub use cartesian_yaw::cartesian_yaw;
pub use general_6r::{general_6r, Formulation, Hint, FORMULATIONS};
pub use pitch_roll::pitch_roll;
pub use planar::planar;
pub use position::{
    position_cartesian, position_intersecting, position_intersecting_prismatic,
    position_one_revolute, position_parallel,
};
pub use spherical::spherical;
pub use spherical_two_intersecting::{
    spherical_two_intersecting, spherical_two_intersecting_by_branch,
    spherical_two_intersecting_prismatic,
};
pub use spherical_two_parallel::{spherical_two_parallel, spherical_two_parallel_by_branch};
pub use srs::{
    arm_angle, arm_angle_intervals, configuration, srs_arm_angle, ArmAngleIntervals, Configuration,
};
pub use three_parallel::three_parallel;
pub use ur::{three_parallel_two_intersecting, three_parallel_two_intersecting_by_branch};

/// How a solver finds the second of a wrist's two solutions (the two roots of q5).
///
/// Write the last three rotations as `rot(a, θa) rot(h5, q5) rot(h6, q6)`, with `a` = h4
/// for a spherical wrist and `a` = h2 ∥ h3 ∥ h4 for the UR family (θa = q4, or θ = q2 ±
/// q3 ± q4). When `a ⟂ h5` and `h5 ⟂ h6` at `q = 0` — an orthogonal wrist — `h6 =
/// rot(h5, o) a` for some `o`, `rot(a, π) rot(h5, x) = rot(h5, −x) rot(a, π)` and
/// `rot(a, π) rot(h6, π) = rot(h5, −2o)`, so `(θa + π, −q5 − 2o, q6 + π)` is the other
/// solution: the other root of q5's equation (`φ ± d` with `φ = −o`) takes θa and q6 from
/// the first by half turns, without a subproblem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WristPair {
    /// Both solutions from the subproblems (any wrist geometry).
    Solve,
    /// The second is the first turned by half turns about `a` and `h6` (the engine proved
    /// the wrist orthogonal, exactly, at expansion time).
    HalfTurn,
}

/// A family's solver for regular poses in lanes (see [`regular`](super::regular)) and its
/// branch-by-branch solver for every pose.
type Solvers = (
    fn(&Geometry<6>, &Pose, &mut Candidates<6, 8>) -> Option<()>,
    fn(&Geometry<6>, &Pose, &[f64; 6], WristPair, &mut Candidates<6, 8>),
);

/// The candidates of a regular pose from the lanes (for an orthogonal wrist), else those of
/// the branch-by-branch solver, into `out` (empty before).
#[inline]
fn regular_first(
    (lanes, by_branch): Solvers,
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    // The lanes leave `out` untouched where they return `None`. The `small-ik` feature
    // leaves them out of the build: every pose one branch after another.
    #[cfg(not(feature = "small-ik"))]
    if pair == WristPair::HalfTurn && lanes(g, pose, out).is_some() {
        return;
    }
    #[cfg(feature = "small-ik")]
    let _ = lanes;
    by_branch(g, pose, free, pair, out);
}

#[cfg(test)]
mod tests {
    //! What the families' tests share.
    use super::*;

    pub(super) type Solver = fn(&Geometry<6>, &Pose, &[f64; 6], WristPair, &mut Candidates<6, 8>);

    /// A random unit vector (the random arms of the families' tests).
    pub(super) fn unit(rng: &mut crate::ik::XorShift64) -> crate::ik::geometry::V3 {
        crate::ik::geometry::V3::new(
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
        )
        .normalize()
    }

    /// What `solver` puts into an empty set of candidates.
    pub(super) fn solved(
        solver: Solver,
        g: &Geometry<6>,
        pose: &Pose,
        free: &[f64; 6],
        pair: WristPair,
    ) -> Candidates<6, 8> {
        let mut out = Candidates::default();
        solver(g, pose, free, pair, &mut out);
        out
    }
}
