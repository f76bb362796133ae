//! Redundancy resolution by gradient projection (Liégeois 1977): joint rates that give the
//! tool twist exactly and spend the remaining freedom climbing a measure — here
//! Yoshikawa's manipulability, whose gradient the generated code has in closed form
//! (`manipulability_gradient`: the generated Hessian and a stack-only SVD).
//!
//! `q̇ = J⁺ ẋ + k (I − J⁺ J) ∇m`: the first term is the least-norm solution of `J q̇ = ẋ`,
//! the second moves in the null space of J — `J (I − J⁺J) = 0`, so it does not disturb the
//! tool — along the part of `∇m` that the task leaves free. For a 7-axis arm the null
//! space is (generically) one-dimensional: the elbow's self-motion. For a non-redundant arm
//! it is empty away from singularities and the step is `J⁻¹ ẋ`.

use crate::adapters::jacobian_matrix;
use crate::error::SolveError;
use crate::linalg::Svd;
use crate::SecondOrderKinematics;
use nalgebra::{SMatrix, SVector};

/// The gain and the rank tolerance of [`gradient_projection`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// `k ≥ 0`: how fast the null-space motion climbs `m` (rad/s per unit of `∇m`).
    pub gain: f64,
    /// Singular values below `tolerance · σ_max` count as zero in `J⁺` (so that a
    /// singular direction becomes part of the null space instead of an unbounded rate).
    pub tolerance: f64,
}

impl Default for Projection {
    /// `k = 1`, tolerance `1e-6`.
    fn default() -> Self {
        Projection {
            gain: 1.0,
            tolerance: 1e-6,
        }
    }
}

/// `q̇ = J⁺ ẋ + k (I − J⁺ J) ∇m` for the world-frame tool twist `xdot = [v; ω]`, with
/// `∇m` the generated `manipulability_gradient`. `J q̇ = ẋ` holds exactly (to rounding)
/// wherever J has full row rank; with `ẋ = 0` the arm moves only in its self-motion,
/// raising `m` (`ṁ = k ‖(I − J⁺J)∇m‖² ≥ 0`). `Err(NonFinite)` for non-finite input.
///
/// ```
/// use kinegen::redundancy::{gradient_projection, Projection};
/// use kinegen::{Kinematics, SecondOrderKinematics};
/// use nalgebra::SVector;
/// kinegen::kinematics! {
///     /// A planar 4R arm: four joints for the three planar rows (vx, vy, ωz), so one
///     /// degree of redundancy. (Its full-J manipulability `√det(J Jᵀ)` is identically
///     /// 0 — a 6×4 J — so here the null-space term is 0 and the step is `J⁺ ẋ`.)
///     struct Arm4;
///     convention: standard,
///     joints: [
///         revolute { a: 1.0, alpha: 0, d: 0 },
///         revolute { a: 0.8, alpha: 0, d: 0 },
///         revolute { a: 0.5, alpha: 0, d: 0 },
///         revolute { a: 0.3, alpha: 0, d: 0 },
///     ],
/// }
/// let q = [0.2, 0.9, -0.4, 0.6];
/// let xdot = SVector::<f64, 6>::new(0.1, -0.05, 0.0, 0.0, 0.0, 0.4);
/// let qd = gradient_projection(&Arm4, &q, &xdot, &Projection::default()).unwrap();
/// let j = Arm4.jacobian(&q);
/// for r in 0..6 {
///     let v: f64 = (0..4).map(|c| j[r][c] * qd[c]).sum();
///     assert!((v - xdot[r]).abs() < 1e-12);
/// }
/// ```
pub fn gradient_projection<R: SecondOrderKinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    xdot: &SVector<f64, 6>,
    projection: &Projection,
) -> Result<SVector<f64, N>, SolveError> {
    if !(q.iter().all(|x| x.is_finite())
        && xdot.iter().all(|x| x.is_finite())
        && projection.gain.is_finite()
        && projection.tolerance.is_finite())
    {
        return Err(SolveError::NonFinite);
    }
    let j = jacobian_matrix(robot, q);
    let pinv = Svd::new(&j)?.pseudo_inverse(projection.tolerance);
    let grad = SVector::<f64, N>::from(robot.manipulability_gradient(q));
    if !grad.iter().all(|x| x.is_finite()) {
        return Err(SolveError::NonFinite);
    }
    let null = SMatrix::<f64, N, N>::identity() - pinv * j;
    Ok(pinv * xdot + null * grad * projection.gain)
}
