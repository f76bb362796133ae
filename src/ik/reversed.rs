//! A family solved on the chain **read from the tool to the base**.
//!
//! Some arms fit a family only backwards: the Franka Panda (joint 7 locked) has a
//! spherical *shoulder* — axes 1, 2, 3 meet — which is the spherical wrist of the chain
//! read from the tool, and axes 6 and 5 meet, the "two intersecting" of that chain. The
//! engine decides this exactly at expansion time (the relations it tests do not depend on
//! the direction), and derives the geometry read backwards there too (the generated
//! `ik_geometry_reversed`; [`Geometry::reversed`] at run time: joint `i` becomes joint
//! `N − 1 − i`, its axis `−R_Mᵀ h` and its point `R_Mᵀ (p − p_M)` as seen from the tool
//! at `q = 0`). At run time the pose is inverted, the family solved on that geometry, and
//! each candidate's joints put back in the robot's order. The angles themselves are the
//! robot's: the negated axes absorb the inverse's negated rotations.
//!
//! A locked joint ([`solve_reversed_locked`]) is locked on the reversed chain: the Panda's
//! joint 7 is that chain's first, whose motion only moves the pose
//! ([`Geometry::lock_at_pose`]).

use super::geometry::{Geometry, Pose};
use super::solutions::Candidates;

/// Adds to `out` (empty before, as the families take it) the candidates of `pose` that
/// `solve` finds on the reversed chain `back` (the robot's geometry read backwards:
/// `ik_geometry_reversed`, or [`Geometry::reversed`]); `free` is in the robot's joint
/// order, as are the candidates added.
///
/// ```
/// use kinegen::ik::geometry::{Geometry, V3, M3};
/// use kinegen::ik::solutions::Candidates;
/// use kinegen::ik::families::{spherical_two_intersecting, WristPair};
/// use kinegen::ik::reversed::solve_reversed;
/// // A spherical shoulder (axes 1, 2, 3 meet at the origin), an elbow, and axes 5 and 6
/// // meeting: the spherical-wrist family read from the tool.
/// let g = Geometry::<6> {
///     h: [V3::z(), V3::y(), V3::z(), V3::y(), V3::z(), V3::y()],
///     p: [V3::zeros(), V3::zeros(), V3::zeros(), V3::new(0.1, 0.0, 0.4),
///         V3::new(0.0, 0.0, 0.8), V3::new(0.0, 0.0, 0.8)],
///     prismatic: [false; 6],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.1, 0.0, 0.9),
/// };
/// let q = [0.3, -0.7, 0.4, 1.1, -0.5, 0.8];
/// let pose = g.fk(&q);
/// let mut out = Candidates::<6, 8>::default();
/// solve_reversed(&g.reversed(), &pose, &[0.0; 6], |g, p, f, o| {
///     spherical_two_intersecting(g, p, f, WristPair::HalfTurn, o)
/// }, &mut out);
/// assert!(out.as_slice().iter().any(|c| {
///     (0..6).all(|i| (c.q[i] - q[i]).abs() < 1e-9)
/// }));
/// ```
#[inline]
pub fn solve_reversed<const N: usize, const K: usize>(
    back: &Geometry<N>,
    pose: &Pose,
    free: &[f64; N],
    solve: impl FnOnce(&Geometry<N>, &Pose, &[f64; N], &mut Candidates<N, K>),
    out: &mut Candidates<N, K>,
) {
    solved_backwards(back, &pose.inverse(), free, solve, out);
}

/// [`solve_reversed`] with the robot's joint `k` (0-based) locked at `q_locked`: `back`
/// is the whole `N`-joint chain read backwards, `free` and the candidates added have the
/// robot's other `M = N − 1` joints in its order (the caller puts the locked one back).
/// The joint is locked on the reversed chain, where it is joint `N − 1 − k`
/// ([`Geometry::lock_at_pose`]: for the robot's last joint only the inverted pose moves).
///
/// ```
/// use kinegen::ik::geometry::{Geometry, V3, M3};
/// use kinegen::ik::solutions::{with_locked, Candidates};
/// use kinegen::ik::families::{spherical_two_intersecting, WristPair};
/// use kinegen::ik::reversed::solve_reversed_locked;
/// // The arm of `solve_reversed`'s example with a seventh joint turning the tool.
/// let g = Geometry::<7> {
///     h: [V3::z(), V3::y(), V3::z(), V3::y(), V3::z(), V3::y(), V3::x()],
///     p: [V3::zeros(), V3::zeros(), V3::zeros(), V3::new(0.1, 0.0, 0.4),
///         V3::new(0.0, 0.0, 0.8), V3::new(0.0, 0.0, 0.8), V3::new(0.1, 0.0, 0.9)],
///     prismatic: [false; 7],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.2, 0.0, 0.9),
/// };
/// let q = [0.3, -0.7, 0.4, 1.1, -0.5, 0.8, 0.6];
/// let mut out = Candidates::<6, 8>::default();
/// solve_reversed_locked(&g.reversed(), &g.fk(&q), 6, q[6], &[0.0; 6], |g, p, f, o| {
///     spherical_two_intersecting(g, p, f, WristPair::HalfTurn, o)
/// }, &mut out);
/// let all = with_locked::<6, 7, 8>(&out, 6, q[6]);
/// assert!(all.as_slice().iter().any(|c| (0..7).all(|i| (c.q[i] - q[i]).abs() < 1e-9)));
/// ```
#[inline]
pub fn solve_reversed_locked<const N: usize, const M: usize, const K: usize>(
    back: &Geometry<N>,
    pose: &Pose,
    k: usize,
    q_locked: f64,
    free: &[f64; M],
    solve: impl FnOnce(&Geometry<M>, &Pose, &[f64; M], &mut Candidates<M, K>),
    out: &mut Candidates<M, K>,
) {
    let (rest, target) = back.lock_at_pose::<M>(N - 1 - k, q_locked, &pose.inverse());
    solved_backwards(&rest, &target, free, solve, out);
}

/// `solve` on the reversed chain `back` and the pose it must reach, `free` and the
/// candidates added in the robot's joint order.
#[inline(always)]
fn solved_backwards<const N: usize, const K: usize>(
    back: &Geometry<N>,
    target: &Pose,
    free: &[f64; N],
    solve: impl FnOnce(&Geometry<N>, &Pose, &[f64; N], &mut Candidates<N, K>),
    out: &mut Candidates<N, K>,
) {
    let free_back: [f64; N] = core::array::from_fn(|i| free[N - 1 - i]);
    // Solved into `out` itself, then the new candidates' joints put back in the robot's
    // order in place: no second set to fill and copy.
    let before = out.as_slice().len();
    solve(back, target, &free_back, out);
    for c in &mut out.as_mut_slice()[before..] {
        c.q.reverse();
    }
}

#[cfg(test)]
mod tests {
    use crate::ik::geometry::examples::{puma, ur5};

    #[test]
    fn the_reversed_chain_reaches_the_inverse_pose() {
        for g in [ur5(), puma()] {
            let q = [0.3, -1.1, 1.4, -0.6, 0.9, 2.0];
            let t = g.fk(&q).inverse();
            let r = g.reversed().fk(&core::array::from_fn(|i| q[5 - i]));
            assert!((t.r - r.r).norm() < 1e-14 && (t.p - r.p).norm() < 1e-14);
            // Read backwards twice: the same arm.
            let twice = g.reversed().reversed();
            let u = twice.fk(&q);
            let v = g.fk(&q);
            assert!((u.r - v.r).norm() < 1e-14 && (u.p - v.p).norm() < 1e-14);
        }
    }
}
