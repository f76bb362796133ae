//! Inverse velocity kinematics: the joint rates `q̇` that produce a tool velocity `ẋ`,
//! given `ẋ = J(q) q̇`. Works for the full 6 × N geometric Jacobian and for task Jacobians
//! (any `M × N`).
//!
//! | method | formula | when |
//! |---|---|---|
//! | [`inverse_velocity`] | `q̇ = J⁻¹ ẋ` (LU, partial pivoting) | square, away from singularities; `Err` at them |
//! | [`pinv_left`] | `J⁺ = (JᵀJ)⁻¹Jᵀ` | full column rank (`M ≥ N`) |
//! | [`pinv_right`] | `J⁺ = Jᵀ(JJᵀ)⁻¹` | full row rank (`M ≤ N`, redundant arms) |
//! | [`pinv_svd`], [`pinv_velocity`] | `J⁺ = V Σ⁺ Uᵀ` | any rank: minimum-norm least squares |
//! | [`dls_velocity`] | `q̇ = Σ σᵢ/(σᵢ²+λ²) vᵢ uᵢᵀ ẋ` | through singularities: bounded, damped only near them |
//! | [`transpose_velocity`] | `q̇ = α Jᵀ ẋ` | cheapest; a descent direction, not the exact inverse |
//!
//! None of them returns inf or NaN: singular or non-finite input gives `Err`, or a bounded
//! damped result for DLS.

use crate::adapters::jacobian_matrix;
use crate::error::SolveError;
use crate::linalg::{all_finite, max_abs, Lu, Svd};
use crate::Kinematics;
use nalgebra::{SMatrix, SVector};

pub use crate::linalg::DEFAULT_TOLERANCE;

/// `q̇ = J⁻¹ ẋ` for a square Jacobian, by LU with partial pivoting.
///
/// `Err(Singular)` when a pivot is below `tolerance · max|Jᵢⱼ|` (e.g. a planar RR arm
/// stretched out, `q₂ = 0`), never inf/NaN.
///
/// ```
/// use kinegen::velocity::{inverse_velocity, DEFAULT_TOLERANCE};
/// use kinegen::SolveError;
/// use nalgebra::{Matrix2, Vector2};
/// // Planar RR (L1 = L2 = 1) at q = (0, π/2): J = [[-1, -1], [1, 0]].
/// let j = Matrix2::new(-1.0, -1.0, 1.0, 0.0);
/// let qd = inverse_velocity(&j, &Vector2::new(0.0, 1.0), DEFAULT_TOLERANCE).unwrap();
/// assert!((j * qd - Vector2::new(0.0, 1.0)).norm() < 1e-15);
/// // Stretched out (q2 = 0): J = [[0, 0], [2, 1]] is singular.
/// let j = Matrix2::new(0.0, 0.0, 2.0, 1.0);
/// assert!(matches!(
///     inverse_velocity(&j, &Vector2::new(1.0, 0.0), DEFAULT_TOLERANCE),
///     Err(SolveError::Singular { .. })
/// ));
/// ```
pub fn inverse_velocity<const N: usize>(
    jacobian: &SMatrix<f64, N, N>,
    xdot: &SVector<f64, N>,
    tolerance: f64,
) -> Result<SVector<f64, N>, SolveError> {
    Lu::new(jacobian, tolerance)?.solve(xdot)
}

/// `J⁻¹` of a square Jacobian (LU), `Err(Singular)` at a singularity.
pub fn jacobian_inverse<const N: usize>(
    jacobian: &SMatrix<f64, N, N>,
    tolerance: f64,
) -> Result<SMatrix<f64, N, N>, SolveError> {
    Lu::new(jacobian, tolerance)?.inverse()
}

/// Left pseudo-inverse `J⁺ = (JᵀJ)⁻¹Jᵀ`, the least-squares inverse of a tall (`M ≥ N`)
/// Jacobian of full column rank. `Err(Singular)` if `JᵀJ` is singular (rank < N; always
/// when `M < N`). Note that `JᵀJ` squares the condition number: the tolerance applies to
/// the pivots of `JᵀJ`.
pub fn pinv_left<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    tolerance: f64,
) -> Result<SMatrix<f64, N, M>, SolveError> {
    let jt = jacobian.transpose();
    let lu = Lu::new(&(jt * jacobian), tolerance)?;
    let mut p = SMatrix::<f64, N, M>::zeros();
    for c in 0..M {
        p.set_column(c, &lu.solve(&jt.column(c).into_owned())?);
    }
    Ok(p)
}

/// Right pseudo-inverse `J⁺ = Jᵀ(JJᵀ)⁻¹`, the minimum-norm inverse of a wide (`M ≤ N`,
/// redundant) Jacobian of full row rank. `Err(Singular)` if an LU pivot of `JJᵀ` is below
/// `tolerance` times its largest entry. That test squares J's conditioning and is not a
/// rank test: at an exact singularity the last pivot can stay above a small tolerance
/// (2.5e-12 measured at a UR5 wrist singularity, `q5 = 0`), and the result is then
/// meaningless. Where the arm may reach a singularity use [`pinv_svd`] or
/// [`dls_velocity`].
pub fn pinv_right<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    tolerance: f64,
) -> Result<SMatrix<f64, N, M>, SolveError> {
    let inv = Lu::new(&(jacobian * jacobian.transpose()), tolerance)?.inverse()?;
    Ok(jacobian.transpose() * inv)
}

/// Moore–Penrose pseudo-inverse by SVD, valid at any rank: singular values below
/// `tolerance · σ_max` are treated as zero. `Err` only for non-finite input.
///
/// ```
/// use kinegen::velocity::pinv_svd;
/// use nalgebra::Matrix2;
/// let j = Matrix2::new(0.0, 0.0, 2.0, 1.0); // rank 1
/// let p = pinv_svd(&j, 1e-12).unwrap();
/// assert!((j * p * j - j).norm() < 1e-14); // J J⁺ J = J
/// ```
pub fn pinv_svd<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    tolerance: f64,
) -> Result<SMatrix<f64, N, M>, SolveError> {
    Ok(Svd::new(jacobian)?.pseudo_inverse(tolerance))
}

/// `q̇ = J⁺ ẋ` by SVD: the minimum-norm joint rates that best achieve `ẋ` (least squares).
pub fn pinv_velocity<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    xdot: &SVector<f64, M>,
    tolerance: f64,
) -> Result<SVector<f64, N>, SolveError> {
    Svd::new(jacobian)?.solve(xdot, tolerance)
}

/// Singularity-adaptive damping for damped least squares (Nakamura & Hanafusa 1986;
/// Chiaverini 1997): no damping while the smallest singular value `σ_min ≥ ε`, and
/// `λ² = (1 − (σ_min/ε)²) λ_max²` below it, so the damping grows smoothly from 0 at
/// `σ_min = ε` to `λ_max` at the singularity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Damping {
    /// Size `ε` of the singular region, in the units of the Jacobian's singular values
    /// (metres for the linear rows of a geometric Jacobian).
    pub epsilon: f64,
    /// Damping `λ_max` reached at the singularity. The joint rates are bounded by roughly
    /// `‖ẋ‖ / (2 λ_max)` there.
    pub lambda_max: f64,
}

impl Default for Damping {
    /// `ε = 0.05`, `λ_max = 0.05`: sized for arms with links of tenths of a metre to metres.
    fn default() -> Self {
        Damping {
            epsilon: 0.05,
            lambda_max: 0.05,
        }
    }
}

impl Damping {
    /// `λ²` for the given smallest singular value.
    pub fn lambda_squared(&self, sigma_min: f64) -> f64 {
        if sigma_min >= self.epsilon || self.epsilon <= 0.0 || self.epsilon.is_nan() {
            0.0
        } else {
            let r = sigma_min / self.epsilon;
            (1.0 - r * r) * self.lambda_max * self.lambda_max
        }
    }
}

/// Damped least squares `q̇ = Jᵀ(JJᵀ + λ²I)⁻¹ ẋ`, computed as `Σ σᵢ/(σᵢ²+λ²) vᵢ uᵢᵀ ẋ` with
/// `λ` from [`Damping`]. Equal to the pseudo-inverse solution away from singularities;
/// bounded at them (directions with `σᵢ = 0` get no motion). `Err` only for non-finite
/// input.
///
/// ```
/// use kinegen::velocity::{dls_velocity, Damping};
/// use nalgebra::{Matrix2, Vector2};
/// let j = Matrix2::new(0.0, 0.0, 2.0, 1.0); // planar RR stretched out: singular
/// let qd = dls_velocity(&j, &Vector2::new(1.0, 1.0), &Damping::default()).unwrap();
/// assert!(qd.iter().all(|v| v.is_finite()));
/// ```
pub fn dls_velocity<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    xdot: &SVector<f64, M>,
    damping: &Damping,
) -> Result<SVector<f64, N>, SolveError> {
    if !all_finite(xdot) {
        return Err(SolveError::NonFinite);
    }
    let svd = Svd::new(jacobian)?;
    Ok(dls_from_svd(&svd, xdot, damping))
}

pub(crate) fn dls_from_svd<const M: usize, const N: usize>(
    svd: &Svd<M, N>,
    xdot: &SVector<f64, M>,
    damping: &Damping,
) -> SVector<f64, N> {
    let l2 = damping.lambda_squared(svd.sigma_min());
    svd.apply_filtered(xdot, |s| {
        let d = s * s + l2;
        if s > 0.0 && d > 0.0 {
            s / d
        } else {
            0.0
        }
    })
}

/// Jacobian-transpose method `q̇ = α Jᵀ ẋ` (α > 0 small): a direction that never increases
/// the task error to first order, without any inversion. `Err(NonFinite)` for non-finite
/// input.
pub fn transpose_velocity<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    xdot: &SVector<f64, M>,
    alpha: f64,
) -> Result<SVector<f64, N>, SolveError> {
    if max_abs(jacobian).is_none() || !all_finite(xdot) || !alpha.is_finite() {
        return Err(SolveError::NonFinite);
    }
    Ok(jacobian.tr_mul(xdot) * alpha)
}

/// `q̇ = J(q)⁻¹ ẋ` for a 6-joint robot and a world-frame twist `ẋ = [v; ω]` of the tool.
pub fn joint_velocities<R: Kinematics<6>>(
    robot: &R,
    q: &[f64; 6],
    xdot: &SVector<f64, 6>,
    tolerance: f64,
) -> Result<SVector<f64, 6>, SolveError> {
    inverse_velocity(&jacobian_matrix(robot, q), xdot, tolerance)
}

/// Damped least squares joint rates for any robot (redundant ones too).
pub fn joint_velocities_dls<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    xdot: &SVector<f64, 6>,
    damping: &Damping,
) -> Result<SVector<f64, N>, SolveError> {
    dls_velocity(&jacobian_matrix(robot, q), xdot, damping)
}
