//! The two factorisations the runtime needs, on fixed-size nalgebra matrices, without
//! allocation and for any `M × N` known at compile time:
//!
//! - [`Lu`]: LU with partial (row) pivoting for square systems, with a relative pivot
//!   tolerance so a singular matrix gives `Err` instead of inf/NaN.
//! - [`Svd`]: singular value decomposition by one-sided (Hestenes) Jacobi rotations.
//!   Jacobi is used instead of nalgebra's bidiagonal SVD because the latter needs
//!   `DimMin` bounds that cannot be stated for a generic `const M, N`; Jacobi is also
//!   accurate for the small singular values that matter near a singularity.

use crate::error::SolveError;
use crate::math::{abs, sqrt};
use nalgebra::{SMatrix, SVector};

/// Relative pivot tolerance used by the convenience functions: a pivot smaller than
/// `DEFAULT_TOLERANCE · max|aᵢⱼ|` counts as zero.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;

/// Largest absolute entry, or `None` if any entry is NaN or infinite.
pub(crate) fn max_abs<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>) -> Option<f64> {
    let mut m = 0.0f64;
    for x in a.iter() {
        if !x.is_finite() {
            return None;
        }
        m = m.max(abs(*x));
    }
    Some(m)
}

pub(crate) fn all_finite<const R: usize>(v: &SVector<f64, R>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// `P A = L U` of a square matrix, `L` unit lower triangular (stored below the diagonal of
/// `lu`), `U` upper triangular.
///
/// ```
/// use kinegen::linalg::Lu;
/// use nalgebra::{Matrix2, Vector2};
/// let lu = Lu::new(&Matrix2::new(0.0, 2.0, 1.0, 1.0), 1e-12).unwrap();
/// assert_eq!(lu.determinant(), -2.0);
/// let x = lu.solve(&Vector2::new(2.0, 3.0)).unwrap();
/// assert!((x - Vector2::new(2.0, 1.0)).norm() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Lu<const N: usize> {
    lu: SMatrix<f64, N, N>,
    perm: [usize; N],
    sign: f64,
}

impl<const N: usize> Lu<N> {
    /// Factorises `a`. `Err(Singular)` if a pivot is below `tolerance · max|aᵢⱼ|` (a zero
    /// matrix is singular), `Err(NonFinite)` for NaN/∞ entries.
    pub fn new(a: &SMatrix<f64, N, N>, tolerance: f64) -> Result<Self, SolveError> {
        let scale = max_abs(a).ok_or(SolveError::NonFinite)?;
        if scale == 0.0 {
            return Err(SolveError::Singular {
                measure: 0.0,
                tolerance,
            });
        }
        let mut lu = *a;
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let mut sign = 1.0;
        for k in 0..N {
            // Partial pivoting: the largest entry of column k at or below the diagonal.
            let mut p = k;
            for i in k + 1..N {
                if abs(lu[(i, k)]) > abs(lu[(p, k)]) {
                    p = i;
                }
            }
            let pivot = lu[(p, k)];
            let measure = abs(pivot) / scale;
            // Also catches a NaN tolerance.
            if measure <= tolerance || tolerance.is_nan() {
                return Err(SolveError::Singular { measure, tolerance });
            }
            if p != k {
                lu.swap_rows(p, k);
                perm.swap(p, k);
                sign = -sign;
            }
            for i in k + 1..N {
                let l = lu[(i, k)] / pivot;
                lu[(i, k)] = l;
                for j in k + 1..N {
                    lu[(i, j)] -= l * lu[(k, j)];
                }
            }
        }
        Ok(Lu { lu, perm, sign })
    }

    /// `det A`, the product of the pivots with the permutation's sign.
    pub fn determinant(&self) -> f64 {
        let mut d = self.sign;
        for i in 0..N {
            d *= self.lu[(i, i)];
        }
        d
    }

    /// Solves `A x = b`; `Err(NonFinite)` for a non-finite `b`, `Err(Overflow)` if the
    /// result is not finite.
    pub fn solve(&self, b: &SVector<f64, N>) -> Result<SVector<f64, N>, SolveError> {
        if !all_finite(b) {
            return Err(SolveError::NonFinite);
        }
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            x[i] = b[self.perm[i]];
        }
        // Forward substitution with the unit lower triangle.
        for i in 0..N {
            let mut s = x[i];
            for j in 0..i {
                s -= self.lu[(i, j)] * x[j];
            }
            x[i] = s;
        }
        // Back substitution with the upper triangle.
        for i in (0..N).rev() {
            let mut s = x[i];
            for j in i + 1..N {
                s -= self.lu[(i, j)] * x[j];
            }
            x[i] = s / self.lu[(i, i)];
        }
        if all_finite(&x) {
            Ok(x)
        } else {
            Err(SolveError::Overflow)
        }
    }

    /// `A⁻¹`, column by column.
    pub fn inverse(&self) -> Result<SMatrix<f64, N, N>, SolveError> {
        let mut inv = SMatrix::<f64, N, N>::zeros();
        for c in 0..N {
            let mut e = SVector::<f64, N>::zeros();
            e[c] = 1.0;
            inv.set_column(c, &self.solve(&e)?);
        }
        Ok(inv)
    }
}

/// Jacobi sweeps before giving up; convergence is quadratic, 6×7 matrices take 6–10.
const MAX_SWEEPS: usize = 60;

/// Thin singular value decomposition `A = U Σ Vᵀ` of an `M × N` matrix with `N` singular
/// values (sorted descending). When `N > M` the last `N − M` are zero (up to rounding) and
/// their `U` columns are zero.
///
/// ```
/// use kinegen::linalg::Svd;
/// use nalgebra::Matrix2x3;
/// let a = Matrix2x3::new(3.0, 0.0, 0.0, 0.0, 0.0, 2.0);
/// let svd = Svd::new(&a).unwrap();
/// assert!((svd.singular_values[0] - 3.0).abs() < 1e-15);
/// assert!((svd.singular_values[1] - 2.0).abs() < 1e-15);
/// assert!(svd.singular_values[2].abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Svd<const M: usize, const N: usize> {
    /// Left singular vectors as columns (unit, or zero where the singular value is zero).
    pub u: SMatrix<f64, M, N>,
    /// Singular values, descending.
    pub singular_values: SVector<f64, N>,
    /// Right singular vectors as columns (orthonormal).
    pub v: SMatrix<f64, N, N>,
}

impl<const M: usize, const N: usize> Svd<M, N> {
    /// Decomposes `a`; `Err(NonFinite)` if it has NaN/∞ entries. Never fails otherwise:
    /// the sweep count is bounded, and Jacobi converges well within it for finite input.
    pub fn new(a: &SMatrix<f64, M, N>) -> Result<Self, SolveError> {
        max_abs(a).ok_or(SolveError::NonFinite)?;
        let mut w = *a; // columns become σⱼ uⱼ
        let mut v = SMatrix::<f64, N, N>::identity();
        let frob2: f64 = a.iter().map(|x| x * x).sum();
        // Columns whose squared norm is below this are treated as zero: rotating them
        // cannot change any result above rounding, and skipping them ends the sweeps.
        let negligible = frob2 * 1e-32;
        for _ in 0..MAX_SWEEPS {
            let mut rotated = false;
            for p in 0..N {
                for q in p + 1..N {
                    let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
                    for i in 0..M {
                        alpha += w[(i, p)] * w[(i, p)];
                        beta += w[(i, q)] * w[(i, q)];
                        gamma += w[(i, p)] * w[(i, q)];
                    }
                    if alpha <= negligible || beta <= negligible {
                        continue;
                    }
                    if abs(gamma) <= 1e-15 * sqrt(alpha * beta) {
                        continue;
                    }
                    rotated = true;
                    // The rotation that makes columns p and q orthogonal (Golub & Van Loan 8.6).
                    let zeta = (beta - alpha) / (2.0 * gamma);
                    let sign = if zeta >= 0.0 { 1.0 } else { -1.0 };
                    let t = sign / (abs(zeta) + sqrt(1.0 + zeta * zeta));
                    let c = 1.0 / sqrt(1.0 + t * t);
                    let s = c * t;
                    for i in 0..M {
                        let (x, y) = (w[(i, p)], w[(i, q)]);
                        w[(i, p)] = c * x - s * y;
                        w[(i, q)] = s * x + c * y;
                    }
                    for i in 0..N {
                        let (x, y) = (v[(i, p)], v[(i, q)]);
                        v[(i, p)] = c * x - s * y;
                        v[(i, q)] = s * x + c * y;
                    }
                }
            }
            if !rotated {
                break;
            }
        }
        let mut sigma = SVector::<f64, N>::zeros();
        for j in 0..N {
            sigma[j] = w.column(j).norm();
        }
        // Selection sort, descending; N is small.
        for i in 0..N {
            let mut best = i;
            for j in i + 1..N {
                if sigma[j] > sigma[best] {
                    best = j;
                }
            }
            if best != i {
                sigma.swap_rows(i, best);
                w.swap_columns(i, best);
                v.swap_columns(i, best);
            }
        }
        let mut u = SMatrix::<f64, M, N>::zeros();
        for j in 0..N {
            if sigma[j] > 0.0 && sigma[j] * sigma[j] > negligible {
                u.set_column(j, &(w.column(j) / sigma[j]));
            } else {
                sigma[j] = 0.0;
            }
        }
        Ok(Svd {
            u,
            singular_values: sigma,
            v,
        })
    }

    /// Number of singular values that can be nonzero: `min(M, N)`.
    pub const RANK_BOUND: usize = if M < N { M } else { N };

    /// The largest singular value.
    pub fn sigma_max(&self) -> f64 {
        if N == 0 {
            0.0
        } else {
            self.singular_values[0]
        }
    }

    /// The smallest of the `min(M, N)` singular values that can be nonzero.
    pub fn sigma_min(&self) -> f64 {
        if Self::RANK_BOUND == 0 {
            0.0
        } else {
            self.singular_values[Self::RANK_BOUND - 1]
        }
    }

    /// Singular values above `tolerance · σ_max`.
    pub fn rank(&self, tolerance: f64) -> usize {
        let cut = tolerance * self.sigma_max();
        self.singular_values
            .iter()
            .filter(|s| **s > cut && **s > 0.0)
            .count()
    }

    /// `x = Σⱼ gⱼ vⱼ (uⱼ · b)` for a filter `g(σ)` on the singular values: `1/σ` gives the
    /// pseudo-inverse, `σ/(σ² + λ²)` damped least squares.
    pub(crate) fn apply_filtered(
        &self,
        b: &SVector<f64, M>,
        mut filter: impl FnMut(f64) -> f64,
    ) -> SVector<f64, N> {
        let mut x = SVector::<f64, N>::zeros();
        for j in 0..N {
            let g = filter(self.singular_values[j]);
            if g != 0.0 {
                let coef = g * self.u.column(j).dot(b);
                x += self.v.column(j) * coef;
            }
        }
        x
    }

    /// Minimum-norm least-squares solution `A⁺ b`, treating singular values below
    /// `tolerance · σ_max` as zero.
    pub fn solve(
        &self,
        b: &SVector<f64, M>,
        tolerance: f64,
    ) -> Result<SVector<f64, N>, SolveError> {
        if !all_finite(b) {
            return Err(SolveError::NonFinite);
        }
        let cut = tolerance * self.sigma_max();
        let x = self.apply_filtered(b, |s| if s > cut && s > 0.0 { 1.0 / s } else { 0.0 });
        if all_finite(&x) {
            Ok(x)
        } else {
            Err(SolveError::Overflow)
        }
    }

    /// The Moore–Penrose pseudo-inverse `A⁺ = V Σ⁺ Uᵀ` (singular values below
    /// `tolerance · σ_max` treated as zero).
    pub fn pseudo_inverse(&self, tolerance: f64) -> SMatrix<f64, N, M> {
        let cut = tolerance * self.sigma_max();
        let mut p = SMatrix::<f64, N, M>::zeros();
        for j in 0..N {
            let s = self.singular_values[j];
            if s > cut && s > 0.0 {
                p += self.v.column(j) * (self.u.column(j).transpose() / s);
            }
        }
        p
    }
}
