//! Newton on the whole arm, for a branch built on an ill-conditioned root: where a
//! quartic's roots cluster (a singular pose of an SP5/SP6 family, where three or four
//! roots meet), rounding moves each by far more than `√ε`, and the subproblems after it
//! carry that error into every joint. The branch is then brought onto the pose by damped
//! Gauss–Newton steps on `fk` itself (damped: at a singular pose the Jacobian is singular
//! too); the best iterate is kept, and `finish` checks it like any other.

use super::geometry::{Geometry, Pose, V3};
use super::subproblems::Fit;
use crate::pose_error::pose_error;
use nalgebra::{Matrix6, Vector6};

/// Gauss–Newton rounds. At a singular solution convergence is linear (about halving the
/// error per round): twenty take an error of 1e-2 below 1e-8 on the way to rounding.
const ROUNDS: usize = 24;

/// `q` moved onto `pose` (see the module); `q` itself where no round improves it.
pub fn polish(g: &Geometry<6>, q: [f64; 6], pose: &Pose) -> [f64; 6] {
    let (mut best, mut best_miss) = (q, f64::INFINITY);
    let mut q = q;
    for _ in 0..ROUNDS {
        let (e, j) = error_and_jacobian(g, &q, pose);
        let miss = e.amax();
        if miss < best_miss {
            (best, best_miss) = (q, miss);
        } else if miss.is_nan() || miss > 2.0 * best_miss {
            // Damped steps that stop improving have reached rounding (or failed).
            break;
        }
        if miss <= 1e-15 * (1.0 + pose.p.amax()) {
            break;
        }
        let jtj = j.transpose() * j;
        let damping = 1e-14 * (0..6).map(|i| jtj[(i, i)]).fold(0.0, f64::max);
        let a = jtj + Matrix6::identity() * damping;
        let Some(step) = a.cholesky().map(|c| c.solve(&(j.transpose() * e))) else {
            break;
        };
        for (qi, s) in q.iter_mut().zip(step.iter()) {
            *qi += s;
        }
    }
    best
}

/// The pose error `[p − p(q); log(R R(q)ᵀ)]` and the world-frame geometric Jacobian at
/// `q`.
fn error_and_jacobian(g: &Geometry<6>, q: &[f64; 6], pose: &Pose) -> (Vector6<f64>, Matrix6<f64>) {
    let (at, j) = jacobian(g, q);
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
/// built on well conditioned), else [`polish`]ed.
#[inline]
pub fn polished(g: &Geometry<6>, q: [f64; 6], pose: &Pose, fit: Fit) -> [f64; 6] {
    if fit <= Fit::Checked {
        q
    } else {
        polish(g, q, pose)
    }
}
