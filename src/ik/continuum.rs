//! A continuum of solutions: where revolute joints turn about **one line** at a
//! configuration — an S-R-S arm's straight elbow puts axes 3 and 5 on one line, its wrist
//! at q6 = 0 axes 5 and 7 — the pose fixes only a signed sum of their angles, and any
//! split of it is a solution. `ik_near` wants the caller's split, and the subproblems give
//! it (the `free` values) where they see the singularity; where rounding hides it from
//! them (a locked joint that leaves the shoulder's axes nearly parallel), the branch is
//! polished onto the pose at some other point of the continuum. [`slid_to_free`] moves
//! it along the continuum to the caller's values.
//!
//! Why the move is exact: write `T(q) = e^{ξ1 q1} ⋯ e^{ξN qN} M`, and `ξ'_k` for joint
//! `k`'s twist seen in the world at `q` (its axis and point there). Turning joint `i` by
//! `δ` is `e^{ξ'_i δ} T(q)`; turning joint `j > i` by `ε` then gives `e^{ξ'_i δ} e^{ξ'_j ε}
//! T(q)` (joint `j`'s world twist taken at `q`, before joint `i` moved). Where the two
//! axes are one line, `ξ'_j = σ ξ'_i` (`σ = ±1`, their directions), and `ε = −σ δ` leaves
//! `T` as it was, whatever the joints between them do.

use super::geometry::{Geometry, Pose};
use super::polish::polished_holding;

/// Axes within this angle (radians), and points within this distance per unit of the
/// arm's size, are one line: a polished singular branch's own rounding is far below, and
/// the re-polish after the move takes up what is left.
const ONE_LINE: f64 = 1e-9;

/// `q` (a solution of `pose`) moved along every continuum it lies on — each set of
/// revolute joints whose axes are one line at `q` — so that all but the last joint of
/// each set take their `free` values, the last what keeps their signed sum: the
/// solution the subproblems give where they see the singularity. Brought onto `pose`
/// again with the moved joints held; `q` as it was where it lies on no continuum, or the
/// moved one does not come within rounding of the pose.
///
/// ```
/// use kinegen::ik::continuum::slid_to_free;
/// use kinegen::ik::geometry::{Geometry, M3, V3};
/// // Three joints about z, then three others: joints 1–3 always share one line.
/// let g = Geometry {
///     h: [V3::z(), V3::z(), V3::z(), V3::x(), V3::y(), V3::x()],
///     p: [V3::zeros(), V3::zeros(), V3::zeros(), V3::new(0.0, 0.0, 0.3),
///         V3::new(0.2, 0.0, 0.3), V3::new(0.2, 0.1, 0.3)],
///     prismatic: [false; 6],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.3, 0.1, 0.3),
/// };
/// let q = [0.5, 0.25, -0.25, 0.3, -0.2, 0.6];
/// let free = [0.1, 0.2, 0.0, 0.0, 0.0, 0.0];
/// let slid = slid_to_free(&g, q, &g.fk(&q), &free);
/// // q1 and q2 take the free values, q3 the rest of the sum 0.5; the others stay.
/// assert_eq!(&slid[..2], &[0.1, 0.2]);
/// assert!((slid[2] - 0.2).abs() < 1e-15);
/// assert!((3..6).all(|i| (slid[i] - q[i]).abs() < 1e-15));
/// ```
pub fn slid_to_free(g: &Geometry<6>, q: [f64; 6], pose: &Pose, free: &[f64; 6]) -> [f64; 6] {
    let (_, axes, points) = g.frames(&q);
    let size = 1.0
        + points
            .iter()
            .map(|p| p.amax())
            .fold(pose.p.amax(), f64::max);
    // `line[j]`: the first joint whose axis is joint j's line.
    let mut line: [usize; 6] = core::array::from_fn(|j| j);
    for j in 1..6 {
        if g.prismatic[j] {
            continue;
        }
        line[j] = (0..j)
            .find(|&i| {
                !g.prismatic[i]
                    && line[i] == i
                    && axes[i].cross(&axes[j]).norm() <= ONE_LINE
                    && (points[j] - points[i]).cross(&axes[i]).norm() <= ONE_LINE * size
            })
            .unwrap_or(j);
    }
    let mut slid = q;
    let mut held = [false; 6];
    for first in 0..6 {
        let members = (first..6).filter(|&k| line[k] == first);
        let Some(last) = members.clone().next_back().filter(|&last| last != first) else {
            continue;
        };
        // The signed sum Σ σk qk is what the pose fixes (σ: each axis's direction
        // against the first's).
        let sign = |k: usize| axes[k].dot(&axes[first]).signum();
        let mut shift = 0.0;
        for k in members.filter(|&k| k != last) {
            shift += sign(k) * (q[k] - free[k]);
            slid[k] = free[k];
            held[k] = true;
        }
        slid[last] = q[last] + sign(last) * shift;
    }
    if slid == q {
        return q;
    }
    match polished_holding(g, slid, pose, &held) {
        (on_pose, true) => on_pose,
        (_, false) => q,
    }
}
