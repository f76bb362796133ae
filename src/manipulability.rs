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

/// The gradient of Yoshikawa's manipulability ([`manipulability`]) with respect to the
/// joint values, from the Jacobian `j` (M × N, plain rows) and the Hessian `h`
/// (`h[k] = ∂J/∂q_k`, as generated code's `hessian` returns it, rows restricted to the
/// same M): `∂w/∂q_k = w · tr(J⁺ H_k) = Σ_i (Π_(l≠i) σ_l) · u_iᵀ H_k v_i` over the
/// `min(M, N)` singular triplets `(σ_i, u_i, v_i)` of J (`u_iᵀ H_k v_i = ∂σ_i/∂q_k`).
///
/// The second form needs no inverse and stays finite near a singularity. At one (some
/// `σ_i = 0`) `w` is not differentiable — it behaves like `|f(q)|` — and the result is 0,
/// the least-norm element of its generalised (Clarke) gradient; with two or more zero
/// singular values `w` is differentiable there and its gradient is 0. `Err(NonFinite)`
/// for NaN or infinite entries. No allocation.
///
/// ```
/// use kinegen::manipulability::manipulability_gradient;
/// // J = diag(q1, 2) along q: w = 2·q1, ∂w/∂q1 = 2, ∂w/∂q2 = 0.
/// let j = [[0.5, 0.0], [0.0, 2.0]];
/// let h = [[[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 0.0]]];
/// let g = manipulability_gradient(&j, &h).unwrap();
/// assert!((g[0] - 2.0).abs() < 1e-15 && g[1].abs() < 1e-15);
/// ```
pub fn manipulability_gradient<const M: usize, const N: usize>(
    j: &[[f64; N]; M],
    h: &[[[f64; N]; M]; N],
) -> Result<[f64; N], SolveError> {
    if h.iter().flatten().flatten().any(|x| !x.is_finite()) {
        return Err(SolveError::NonFinite);
    }
    let svd = Svd::new(&SMatrix::<f64, M, N>::from_fn(|r, c| j[r][c]))?;
    let k = Svd::<M, N>::RANK_BOUND;
    let sigma = &svd.singular_values;
    let mut out = [0.0; N];
    for i in 0..k {
        // Π_(l≠i) σ_l, without dividing by σ_i.
        let weight: f64 = (0..k).filter(|&l| l != i).map(|l| sigma[l]).product();
        if weight == 0.0 || sigma[i] == 0.0 {
            continue;
        }
        let (u, v) = (svd.u.column(i), svd.v.column(i));
        for (o, hk) in out.iter_mut().zip(h) {
            let mut d = 0.0;
            for (r, row) in hk.iter().enumerate() {
                for (c, x) in row.iter().enumerate() {
                    d += u[r] * x * v[c];
                }
            }
            *o += weight * d;
        }
    }
    Ok(out)
}

/// [`manipulability_gradient`] of `f32` arrays (what `scalar: f32` robots generate),
/// computed in `f64` and rounded once.
pub fn manipulability_gradient_f32<const M: usize, const N: usize>(
    j: &[[f32; N]; M],
    h: &[[[f32; N]; M]; N],
) -> Result<[f32; N], SolveError> {
    let j64 = j.map(|r| r.map(f64::from));
    let h64 = h.map(|m| m.map(|r| r.map(f64::from)));
    Ok(manipulability_gradient(&j64, &h64)?.map(|x| x as f32))
}
