//! Newton on the whole arm, for a branch built on an ill-conditioned root: where a
//! quartic's roots cluster (a singular pose of an SP5/SP6 family, where three or four
//! roots meet), rounding moves each by far more than `√ε`, and the subproblems after it
//! carry that error into every joint. The branch is then brought onto the pose by damped
//! Gauss–Newton steps on `fk` itself (damped: at a singular pose the Jacobian is singular
//! too); a step that lands worse is retried shorter from the best iterate (across the
//! fold of a singular solution a full step overshoots); the best iterate is kept, and
//! `finish` checks it like any other. Where even that stalls (beside a close pair of
//! solutions, whose Jacobian is nearly singular), [`levenberg_marquardt`]'s adaptive
//! damping still converges.

use super::geometry::{Geometry, Pose, V3};
use super::solutions::{pose_matrix, residual};
use super::subproblems::{wrap, Fit};
use crate::pose_error::pose_error;
use nalgebra::{Matrix6, Vector6};

/// Gauss–Newton rounds. At a singular solution convergence is linear (about halving the
/// error per round): twenty take an error of 1e-2 below 1e-8 on the way to rounding.
const ROUNDS: usize = 24;

/// `q` moved onto `pose` (see the module); `q` itself where no round improves it.
pub fn polish(g: &Geometry<6>, q: [f64; 6], pose: &Pose) -> [f64; 6] {
    polish_holding(g, q, pose, &[false; 6])
}

/// [`polish`] with the `held` joints kept where they are (their Jacobian columns left out).
fn polish_holding(g: &Geometry<6>, q: [f64; 6], pose: &Pose, held: &[bool; 6]) -> [f64; 6] {
    let (mut best, mut best_miss) = (q, f64::INFINITY);
    // The step taken from `best`, and how much of it: near a singular solution a full
    // Gauss–Newton step can overshoot (the model is quadratic across the fold), and a
    // shorter one still gains.
    let (mut best_step, mut scale) = (Vector6::zeros(), 1.0);
    let mut q = q;
    let size = 1.0 + pose.p.amax();
    for _ in 0..ROUNDS {
        let (e, j) = error_and_jacobian(g, &q, pose, held);
        let miss = e.amax();
        if miss.is_nan() || miss > 2.0 * best_miss {
            // Worse: within rounding's reach of the pose, done, and far from it (a
            // branch built on a spurious root) not worth more; else back to the best
            // iterate with a quarter of its step, twice at most (measured on the CRX's and
            // the Gen3's special poses: a third quartering found nothing more).
            scale *= 0.25;
            if best_miss <= 1e-12 * size || best_miss > 1e-2 * size || scale < 0.05 {
                break;
            }
            q = step_from(&best, &best_step, scale);
            continue;
        }
        let improved = miss < best_miss;
        if improved {
            best_miss = miss;
            best = q;
        }
        if miss <= 1e-15 * size {
            break;
        }
        let jtj = j.transpose() * j;
        let damping = 1e-14 * (0..6).map(|i| jtj[(i, i)]).fold(0.0, f64::max);
        let a = jtj + Matrix6::identity() * damping;
        let Some(step) = a.cholesky().map(|c| c.solve(&(j.transpose() * e))) else {
            break;
        };
        if improved {
            (best_step, scale) = (step, 1.0);
        }
        q = step_from(&q, &step, 1.0);
    }
    best
}

/// How far `fk(q)` is from `pose`: the largest entry error, as `finish` measures it (what
/// a polished branch is judged by).
pub(crate) fn pose_miss(g: &Geometry<6>, pose: &Pose, q: &[f64; 6]) -> f64 {
    residual(&pose_matrix(&g.fk(q)), pose)
}

/// Levenberg–Marquardt on `fk` from `q` towards `pose`, for up to `rounds` steps: where
/// [`polish`]'s Gauss–Newton steps stall — near a solution whose Jacobian is nearly
/// singular (two solutions close together), each full step overshoots along the
/// near-null direction and the quartered retries give up. The damping `μ` follows the
/// gain ratio of each step (Nielsen's rule: Madsen, Nielsen and Tingleff, *Methods for
/// non-linear least squares problems*, 2004), so it shrinks where the model holds and
/// grows where it does not; convergence near such a solution is linear, so it can take
/// hundreds of steps. The best iterate is returned.
pub fn levenberg_marquardt(g: &Geometry<6>, q: [f64; 6], pose: &Pose, rounds: usize) -> [f64; 6] {
    levenberg_marquardt_holding(g, q, pose, rounds, &[false; 6])
}

/// [`levenberg_marquardt`] with the `held` joints kept where they are.
fn levenberg_marquardt_holding(
    g: &Geometry<6>,
    q: [f64; 6],
    pose: &Pose,
    rounds: usize,
    held: &[bool; 6],
) -> [f64; 6] {
    let size = 1.0 + pose.p.amax();
    let (mut e, mut j) = error_and_jacobian(g, &q, pose, held);
    let (mut q, mut cost) = (q, e.norm_squared());
    let jtj = j.transpose() * j;
    let mut mu = 1e-6 * (0..6).map(|i| jtj[(i, i)]).fold(0.0, f64::max);
    let mut nu = 2.0;
    for _ in 0..rounds {
        let miss = e.amax();
        if miss.is_nan() || miss <= 1e-15 * size {
            break;
        }
        let (jtj, grad) = (j.transpose() * j, j.transpose() * e);
        let a = jtj + Matrix6::identity() * mu;
        let Some(step) = a.cholesky().map(|c| c.solve(&grad)) else {
            break;
        };
        let next = step_from(&q, &step, 1.0);
        let (e2, j2) = error_and_jacobian(g, &next, pose, held);
        let cost2 = e2.norm_squared();
        // The reduction the linear model predicts, hᵀ(μh + g) for the cost ‖e‖².
        let predicted = step.dot(&(step * mu + grad));
        let gain = (cost - cost2) / predicted;
        if gain > 0.0 && cost2.is_finite() {
            (q, cost, e, j) = (next, cost2, e2, j2);
            let t = 2.0 * gain - 1.0;
            mu *= f64::max(1.0 / 3.0, 1.0 - t * t * t);
            nu = 2.0;
        } else {
            mu *= nu;
            nu *= 2.0;
            // Steps too short to move: done (a NaN'd damping too).
            if mu.is_nan() || mu >= 1e12 * (1.0 + jtj.amax()) {
                break;
            }
        }
    }
    q
}

/// `q + scale · step`.
fn step_from(q: &[f64; 6], step: &Vector6<f64>, scale: f64) -> [f64; 6] {
    core::array::from_fn(|i| q[i] + scale * step[i])
}

/// The pose error `[p − p(q); log(R R(q)ᵀ)]` and the world-frame geometric Jacobian at
/// `q`, the columns of the `held` joints zero (no step moves them).
fn error_and_jacobian(
    g: &Geometry<6>,
    q: &[f64; 6],
    pose: &Pose,
    held: &[bool; 6],
) -> (Vector6<f64>, Matrix6<f64>) {
    let (at, mut j) = jacobian(g, q);
    for (k, _) in held.iter().enumerate().filter(|(_, &h)| h) {
        j.column_mut(k).fill(0.0);
    }
    (pose_error(&pose.p, &pose.r, &at.p, &at.r), j)
}

/// The tool pose and the world-frame geometric Jacobian at `q`.
fn jacobian(g: &Geometry<6>, q: &[f64; 6]) -> (Pose, Matrix6<f64>) {
    let (at, axes, points) = g.frames(q);
    let mut j = Matrix6::zeros();
    for i in 0..6 {
        let (lin, ang) = if g.prismatic[i] {
            (axes[i], V3::zeros())
        } else {
            (axes[i].cross(&(at.p - points[i])), axes[i])
        };
        for k in 0..3 {
            j[(k, i)] = lin[k];
            j[(k + 3, i)] = ang[k];
        }
    }
    (at, j)
}

/// How far from singular the arm is at `q`: `|det J|` over the product of the columns'
/// norms (Hadamard's ratio: 1 for orthogonal columns, 0 at a singularity), for solvers
/// whose branches are not built by subproblems that see the singularity.
pub fn hadamard_ratio(g: &Geometry<6>, q: &[f64; 6]) -> f64 {
    let (_, j) = jacobian(g, q);
    let norms: f64 = j.column_iter().map(|c| c.norm()).product();
    if norms > 0.0 {
        j.determinant().abs() / norms
    } else {
        0.0
    }
}

/// `q` as it is where its fit is [`Fit::Exact`] or [`Fit::Checked`] (every root it was
/// built on well conditioned), else [`polish`]ed — and where Gauss–Newton stalls short
/// of the pose but near it, given [`levenberg_marquardt`]'s damped steps too.
///
/// The stall is real: a quartic's near-double root that is no singularity of the arm
/// (two (q1, q5) pairs 8e-7 rad apart, q5 0.23 rad apart) left a branch of a reachable
/// pose 9e-11 off after [`polish`], 1.05e-10 as `finish` measures it — over
/// `EXACT_TOLERANCE`, so flagged least squares; damped steps took it to 2e-16 (a random
/// three-parallel table read backwards, `tests/ik_random_tables.rs`).
#[inline]
pub fn polished(g: &Geometry<6>, q: [f64; 6], pose: &Pose, fit: Fit) -> [f64; 6] {
    if fit <= Fit::Checked {
        return q;
    }
    polished_holding(g, q, pose, &[false; 6]).0
}

/// [`polished`] for a branch on a continuum of solutions ([`Fit::Free`]) whose `free`
/// joints took the caller's values: Gauss–Newton's least-norm steps would move them
/// along it (7.8e-7 rad on the iiwa at a straight elbow, where only q3 + q5 is fixed), so
/// they are held first; where the others alone do not bring it within rounding of the
/// pose (a joint that equals its free value by chance, and must move), all are polished.
pub fn polished_keeping(
    g: &Geometry<6>,
    q: [f64; 6],
    pose: &Pose,
    fit: Fit,
    free: &[f64; 6],
) -> [f64; 6] {
    let held: [bool; 6] =
        core::array::from_fn(|i| fit == Fit::Free && (q[i] == free[i] || q[i] == wrap(free[i])));
    if !held.contains(&true) {
        return polished(g, q, pose, fit);
    }
    match polished_holding(g, q, pose, &held) {
        (kept, true) => kept,
        (_, false) => polished(g, q, pose, fit),
    }
}

/// [`polished`] with the `held` joints kept where they are; whether it converged (within
/// rounding of the pose).
pub(crate) fn polished_holding(
    g: &Geometry<6>,
    q: [f64; 6],
    pose: &Pose,
    held: &[bool; 6],
) -> ([f64; 6], bool) {
    let q = polish_holding(g, q, pose, held);
    let size = 1.0 + pose.p.amax();
    let miss = pose_miss(g, pose, &q);
    // Converged already, or too far for a branch that reaches the pose
    // (its least-squares nearest: damped steps would only spend their rounds).
    if miss <= STALLED.0 * size {
        return (q, true);
    }
    if miss > STALLED.1 * size || miss.is_nan() {
        return (q, false);
    }
    let damped = levenberg_marquardt_holding(g, q, pose, DAMPED_ROUNDS, held);
    let damped_miss = pose_miss(g, pose, &damped);
    if damped_miss < miss {
        (damped, damped_miss <= STALLED.0 * size)
    } else {
        (q, false)
    }
}

/// The misses (per unit of the arm's size) between which [`polished`] tries damped steps
/// after Gauss–Newton: above what [`polish`] calls within rounding's reach (1e-12), at
/// most the near-miss a reaching branch can show (`NEAR_MISS`, 1e-5; a branch further
/// off is the nearest of a pose out of its reach).
const STALLED: (f64, f64) = (1e-12, crate::ik::solutions::NEAR_MISS);

/// Levenberg–Marquardt steps for a branch Gauss–Newton left off the pose (in [`polished`]
/// and the general 6R's tracking): on the self-tests (`tests/ik_closed_form.rs`) the
/// general 6R misses no more poses with 200 than with 2 000.
pub(crate) const DAMPED_ROUNDS: usize = 200;
