//! Two branches of one **double root**: at a singular configuration two solutions meet,
//! and rounding splits the root they share into two branches a little apart — by ~1e-8
//! (an eigenvalue's) to ~1e-6 rad (Newton's linear convergence onto a singular solution,
//! a grazing subproblem's square root). [`merge_double_roots`] makes them one, flagged
//! singular, as a subproblem that sees the double root gives it.

use super::geometry::{Geometry, Pose};
use super::polish::polish;
use super::solutions::{Candidate, Candidates};
use super::subproblems::{wrap, Fit};
use crate::math::abs;

/// Branches closer than this in every joint (radians) are one solution twice: a double
/// root at a singular pose, which rounding splits by ~1e-8 (eigenvalues) to ~1e-6
/// (Newton's linear convergence at a singularity). Two regular solutions are never this
/// close but at a pose within rounding of a singular one.
pub const DOUBLE_ROOT: f64 = 2e-6;

/// Merges the branches within [`DOUBLE_ROOT`] of each other into their mean, brought back
/// onto the pose by [`polish`] and flagged [`Fit::Double`]; the others stay as they are,
/// in their order.
///
/// ```
/// use kinegen::ik::double_root::merge_double_roots;
/// use kinegen::ik::geometry::{Geometry, M3, V3};
/// use kinegen::ik::solutions::Candidates;
/// use kinegen::ik::subproblems::Fit;
/// let unit = |x: f64, y: f64, z: f64| V3::new(x, y, z).normalize();
/// let g = Geometry {
///     h: [unit(0.0, 0.0, 1.0), unit(0.1, 1.0, 0.2), unit(0.3, 0.9, -0.1),
///         unit(1.0, 0.2, 0.1), unit(0.2, 1.0, -0.3), unit(0.9, 0.1, 0.4)],
///     p: [V3::zeros(), V3::new(0.05, 0.0, 0.3), V3::new(0.4, 0.1, 0.35),
///         V3::new(0.5, 0.05, 0.6), V3::new(0.7, 0.12, 0.55), V3::new(0.8, 0.0, 0.6)],
///     prismatic: [false; 6],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.9, 0.0, 0.65),
/// };
/// let q = [0.3, -0.7, 0.4, 1.1, -0.5, 0.8];
/// let mut c = Candidates::<6, 8>::default();
/// c.push(q.map(|x| x + 1e-7), Fit::Checked);
/// c.push([1.0; 6], Fit::Checked);
/// c.push(q.map(|x| x - 1e-7), Fit::Checked);
/// merge_double_roots(&g, &g.fk(&q), &mut c);
/// assert_eq!(c.as_slice().len(), 2);
/// assert_eq!(c.as_slice()[0].fit, Fit::Double);
/// assert!((0..6).all(|i| (c.as_slice()[0].q[i] - q[i]).abs() < 1e-12));
/// assert_eq!(c.as_slice()[1].q, [1.0; 6]);
/// ```
pub fn merge_double_roots<const K: usize>(g: &Geometry<6>, pose: &Pose, c: &mut Candidates<6, K>) {
    let all = *c;
    let items = all.as_slice();
    let mut used = [false; K];
    let mut kept = 0;
    for i in 0..items.len() {
        if used[i] {
            continue;
        }
        let (mut sum, mut count, mut fit) = (items[i].q, 1.0, items[i].fit);
        for j in i + 1..items.len() {
            if !used[j] && within(&items[i].q, &items[j].q, DOUBLE_ROOT) {
                used[j] = true;
                for (s, (a, b)) in sum.iter_mut().zip(items[i].q.iter().zip(&items[j].q)) {
                    // Whole turns apart counts as near: add the difference, not the value.
                    *s += a + wrap(b - a);
                }
                count += 1.0;
                fit = Fit::Double;
            }
        }
        let q = if count > 1.0 {
            polish(g, sum.map(|s| s / count), pose).map(wrap)
        } else {
            items[i].q
        };
        c.as_mut_slice()[kept] = Candidate { q, fit };
        kept += 1;
    }
    c.truncate(kept);
}

/// Every joint of `a` within `tol` radians of `b`'s, whole turns apart counting as none.
#[inline]
pub fn within(a: &[f64; 6], b: &[f64; 6], tol: f64) -> bool {
    apart(a, b) < tol
}

/// The largest joint difference of `a` and `b` in radians, whole turns apart counting as
/// none (infinite where one is not a number: never within anything).
#[inline]
pub fn apart(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| abs(wrap(x - y)))
        .fold(
            0.0,
            |m, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        )
}
