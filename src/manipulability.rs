//! Measures of how far a Jacobian is from a singularity (Yoshikawa), for any `M × N`,
//! from the singular values `σ₁ ≥ … ≥ σₖ`, `k = min(M, N)`, of a stack-only SVD.
//!
//! The names follow the Robotics Toolbox's `manipulability(q, axes=…)`:
//! [`manipulability`] of the full 6×N Jacobian (`axes="all"`), [`manipulability_trans`]
//! of its linear rows `[vx vy vz]` (`"trans"`), [`manipulability_rot`] of its angular
//! rows `[ωx ωy ωz]` (`"rot"`), and [`manipulability_task`] of a robot's task rows.
//!
//! # Accuracy near a singularity
//!
//! A Jacobian computed in `f64` is the exact one plus rounding of about `ε·σ₁`
//! (`ε = 2.2e-16`), and that moves each singular value by as much (Weyl). So
//! `w = σ₁⋯σₘ` has an absolute error of about `ε·σ₁ᵐ`: at an exact singularity it comes
//! out as a number of that size, not 0, and its *relative* error grows like `σ₁/σₘ` as
//! `σₘ → 0`. Computing `√det(J Jᵀ)` instead — as the Robotics Toolbox and most code do —
//! rounds the determinant to about `ε·σ₁²ᵐ` and its square root to about `√ε·σ₁ᵐ`
//! (`√ε ≈ 1.5e-8`): near a singularity, expect two such values to agree only to that
//! (measured on the UR5 in `tests/runtime_velocity.rs`).

use crate::error::SolveError;
use crate::linalg::Svd;
use crate::TaskKinematics;
use nalgebra::SMatrix;

/// Yoshikawa's manipulability `w = √det(J Jᵀ)`: `σ₁ σ₂ ⋯ σₘ` for `M ≤ N`, and 0 for a
/// tall `M > N` Jacobian, whose `J Jᵀ` has rank ≤ N < M (a planar arm's 6×2 Jacobian:
/// it cannot move in all six directions). For the volume of the velocity ellipsoid in
/// the subspace a tall `J` reaches, `√det(Jᵀ J)`, pass `j.transpose()`. Computed from the
/// singular values, so it is never the square root of a rounding-negative determinant;
/// see the [module docs](self) for its accuracy near a singularity.
///
/// ```
/// use kinegen::manipulability::manipulability;
/// use nalgebra::{Matrix2, Matrix3x2};
/// let w = manipulability(&Matrix2::new(2.0, 0.0, 0.0, 3.0)).unwrap();
/// assert!((w - 6.0).abs() < 1e-12);
/// let tall = Matrix3x2::new(2.0, 0.0, 0.0, 3.0, 0.0, 0.0);
/// assert_eq!(manipulability(&tall).unwrap(), 0.0);
/// assert!((manipulability(&tall.transpose()).unwrap() - 6.0).abs() < 1e-12);
/// ```
pub fn manipulability<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
) -> Result<f64, SolveError> {
    Ok(yoshikawa(&Svd::new(j)?))
}

/// `σ₁⋯σₘ` for `M ≤ N`, else 0: `√det(J Jᵀ)` from an SVD of the `M × N` matrix.
fn yoshikawa<const M: usize, const N: usize>(svd: &Svd<M, N>) -> f64 {
    if M > N {
        return 0.0;
    }
    svd.singular_values.iter().take(M).product()
}

/// [`manipulability`] of the linear-velocity rows `[vx vy vz]` of a 6×N Jacobian
/// (the Robotics Toolbox's `axes="trans"`): how well the tool point can move.
pub fn manipulability_trans<const N: usize>(j: &SMatrix<f64, 6, N>) -> Result<f64, SolveError> {
    manipulability(&j.fixed_rows::<3>(0).into_owned())
}

/// [`manipulability`] of the angular-velocity rows `[ωx ωy ωz]` of a 6×N Jacobian
/// (`axes="rot"`): how well the tool frame can turn.
pub fn manipulability_rot<const N: usize>(j: &SMatrix<f64, 6, N>) -> Result<f64, SolveError> {
    manipulability(&j.fixed_rows::<3>(3).into_owned())
}

/// [`manipulability`] of a robot's task Jacobian (its rows
/// [`TaskKinematics::TASK_ROWS`]) at `q`: for a planar arm with task `[x, y]`,
/// `L1 L2 |sin q2|`, where the full 6×2 Jacobian gives 0.
pub fn manipulability_task<R: TaskKinematics<N, M>, const N: usize, const M: usize>(
    robot: &R,
    q: &[f64; N],
) -> Result<f64, SolveError> {
    manipulability(&crate::adapters::task_jacobian_matrix(robot, q))
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
        yoshikawa: yoshikawa(&svd),
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
/// singular values `w` is differentiable there and its gradient is 0. For a tall
/// `M > N` Jacobian [`manipulability`] is identically 0, and so is its gradient (for the
/// rows a planar arm reaches use its task rows, `manipulability_task_gradient`).
/// `Err(NonFinite)` for NaN or infinite entries. No allocation.
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
    if M > N {
        return Ok([0.0; N]);
    }
    let k = M;
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
