//! Measures of how far a Jacobian is from a singularity (Yoshikawa), for any `M × N`,
//! from the singular values `σ₁ ≥ … ≥ σₖ`, `k = min(M, N)`, of a stack-only SVD.

use crate::error::SolveError;
use crate::linalg::Svd;
use nalgebra::SMatrix;

/// Yoshikawa's manipulability `w = √det(J Jᵀ) = σ₁ σ₂ ⋯ σₖ` (for `M ≤ N`; for a tall
/// `M > N` Jacobian `det(J Jᵀ) = 0` and this returns `√det(Jᵀ J)` instead, the volume of
/// the velocity ellipsoid in the reachable subspace). Computed from the singular values,
/// so it is never the square root of a rounding-negative determinant.
///
/// ```
/// use kinegen::manipulability::manipulability;
/// use nalgebra::Matrix2;
/// let w = manipulability(&Matrix2::new(2.0, 0.0, 0.0, 3.0)).unwrap();
/// assert!((w - 6.0).abs() < 1e-12);
/// ```
pub fn manipulability<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
) -> Result<f64, SolveError> {
    let svd = Svd::new(j)?;
    Ok(svd
        .singular_values
        .iter()
        .take(Svd::<M, N>::RANK_BOUND)
        .product())
}

/// The smallest of the `min(M, N)` singular values: the slowest direction's gain, zero at a
/// singularity.
pub fn smallest_singular_value<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
) -> Result<f64, SolveError> {
    Ok(Svd::new(j)?.sigma_min())
}

/// Condition number `σ₁ / σₖ` (≥ 1). At an exact singularity (`σₖ = 0`) it is `+∞` — a
/// measure, not a solver output, so infinity is the honest value; a zero matrix gives `+∞`
/// too.
pub fn condition_number<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
) -> Result<f64, SolveError> {
    let svd = Svd::new(j)?;
    let (max, min) = (svd.sigma_max(), svd.sigma_min());
    Ok(if min > 0.0 { max / min } else { f64::INFINITY })
}

/// All three measures from one SVD.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Manipulability {
    /// `√det(J Jᵀ)`, see [`manipulability`].
    pub yoshikawa: f64,
    /// See [`smallest_singular_value`].
    pub sigma_min: f64,
    /// See [`condition_number`].
    pub condition_number: f64,
}

/// [`manipulability`], [`smallest_singular_value`] and [`condition_number`] together.
pub fn measures<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
) -> Result<Manipulability, SolveError> {
    let svd = Svd::new(j)?;
    let (max, min) = (svd.sigma_max(), svd.sigma_min());
    Ok(Manipulability {
        yoshikawa: svd
            .singular_values
            .iter()
            .take(Svd::<M, N>::RANK_BOUND)
            .product(),
        sigma_min: min,
        condition_number: if min > 0.0 { max / min } else { f64::INFINITY },
    })
}
