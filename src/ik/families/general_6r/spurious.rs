//! Step 4's eight spurious eigenvalues — `x = ±i`, four times each — taken out before the
//! QR: the 24 × 24 companion matrix becomes a 16 × 16 one with the other eigenvalues, the
//! sixteen a general 6R can have. (Raghavan and Roth: the pencil's determinant, of degree
//! 24, has the factor `(1 + x²)⁴`.) Francis's QR's work grows with the cube of the size;
//! measured on the Jaco, 345 k instructions for the 24 × 24 against 177 k for the 16 × 16
//! plus 94 k for taking the eight out.
//!
//! Where they come from: at `x = i` the half-angle's `1 + x²` vanishes, so each equation
//! loses the part that does not turn with the eigen joint, and each vector quantity `w`
//! keeps only `w⊥ + i he × w⊥` (`w⊥` across the eigen axis `he`) — a multiple of the one
//! complex vector `u + i he × u`. At `x = i` the six equations are then combinations of
//! four polynomials, one per vector quantity ([`System::spurious`]: the 6 × 4 complex
//! coefficients `c`), and two complex combinations `y` of the six vanish for every x4, x5:
//! `yᵀ c = 0`. Each `y` gives two left null vectors of `M(i)`, `(y, 0)` and `(0, y)` (the
//! rows `e` and `x4 · e`), and each of those a left eigenvector `(z1, z2)` of the
//! companion `[[0, I], [−U, −W]]` for its eigenvalue `μ` at `x = i` (`i`, or `−i` where
//! the companion is the reversed pencil's): `z2ᵀ = yᵀ A`, `z1ᵀ = z2ᵀ (W + μ)` (`A` the
//! lead matrix, `W = A⁻¹ B`). Their real and imaginary parts span an 8-dimensional left
//! invariant subspace; the orthogonal `H` (eight Householder reflections) whose first
//! eight columns span it makes `Hᵀ L H` block lower triangular, `[[Λ, 0], [·, L₂₂]]`, and
//! `L₂₂` holds the other sixteen eigenvalues.
//!
//! Checked, not trusted: where `c` has rank below four, the eight vectors are dependent,
//! or the upper right block is not zero to rounding, [`deflated`] gives `None` and the
//! caller takes the eigenvalues of the whole 24 × 24 matrix.

use super::elimination::System;
use crate::math::{abs, sqrt};

/// A Householder reflection `I − β v vᵀ` acting on the entries `from..` of an
/// `N`-vector.
struct Reflection<const N: usize> {
    v: [f64; N],
    beta: f64,
    from: usize,
}

impl<const N: usize> Reflection<N> {
    /// The reflection taking `x[from..]` onto a multiple of `e_from`, and that multiple
    /// (the triangular factor's diagonal entry).
    fn new(x: &[f64; N], from: usize) -> (Self, f64) {
        let norm2: f64 = x[from..].iter().map(|a| a * a).sum();
        let alpha = if x[from] > 0.0 {
            -sqrt(norm2)
        } else {
            sqrt(norm2)
        };
        let mut v = [0.0; N];
        v[from..].copy_from_slice(&x[from..]);
        v[from] -= alpha;
        // vᵀv = 2 (‖x‖² − α x_from).
        let vv = 2.0 * (norm2 - alpha * x[from]);
        let beta = if vv > 0.0 { 2.0 / vv } else { 0.0 };
        (Reflection { v, beta, from }, alpha)
    }

    /// `P B P` in place: `B − β v wᵀ − β u vᵀ + β² (vᵀ u) v vᵀ` with `wᵀ = vᵀ B`,
    /// `u = B v` — row by row, where a column at a time would gather.
    fn similarity(&self, b: &mut [[f64; N]; N]) {
        let (v, beta) = (&self.v, self.beta);
        let (mut w, mut u) = ([0.0; N], [0.0; N]);
        for (i, row) in b.iter().enumerate() {
            for (wj, x) in w.iter_mut().zip(row) {
                *wj += v[i] * x;
            }
            u[i] = row.iter().zip(v).map(|(x, vj)| x * vj).sum();
        }
        let s = beta * beta * v.iter().zip(&u).map(|(a, c)| a * c).sum::<f64>();
        for (i, row) in b.iter_mut().enumerate() {
            let (a, c) = (beta * v[i], beta * u[i] - s * v[i]);
            for ((x, wj), vj) in row.iter_mut().zip(&w).zip(v) {
                *x -= a * wj + c * vj;
            }
        }
    }

    fn apply(&self, x: &mut [f64; N]) {
        let (x, v) = (&mut x[self.from..], &self.v[self.from..]);
        let s = x.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() * self.beta;
        for (xi, vi) in x.iter_mut().zip(v) {
            *xi -= s * vi;
        }
    }
}

/// Below this, relative to the largest, a triangular factor's diagonal entry is a rank
/// lost: `c` of rank below four, or dependent eigenvectors.
const RANK: f64 = 1e-8;

/// Householder QR of eight `columns` (reduced in place): the reflections, or `None` where
/// a diagonal entry of the triangular factor is below [`RANK`] of the largest or not a
/// number (the columns dependent).
fn qr<const N: usize>(columns: &mut [[f64; N]; 8]) -> Option<[Option<Reflection<N>>; 8]> {
    let mut reflections: [Option<Reflection<N>>; 8] = Default::default();
    let mut diagonal = [0.0f64; 8];
    for k in 0..8 {
        for done in reflections.iter().take(k).flatten() {
            done.apply(&mut columns[k]);
        }
        let (h, alpha) = Reflection::new(&columns[k], k);
        diagonal[k] = abs(alpha);
        reflections[k] = Some(h);
    }
    let largest = diagonal.iter().fold(0.0f64, |m, &d| m.max(d));
    if !largest.is_finite() || diagonal.iter().any(|&d| d.is_nan() || d <= RANK * largest) {
        return None;
    }
    Some(reflections)
}

/// The upper right block of `Hᵀ L H` must be below this relative to `L`'s largest entry
/// (rounding: measured at most 1.5e-15 over the 20 180 systems of the Jaco's bench poses).
const DEFLATED: f64 = 1e-10;

/// The companion matrix `l` of `sys` with its eight eigenvalues at `x = ±i` taken out:
/// a 16 × 16 matrix with the other sixteen, or `None` (see the module). Either way `l`
/// is left similar to what it was — the same eigenvalues — for the caller to fall back
/// on: transformed in place, not copied (the Cortex-M4F's stack).
pub(super) fn deflated(l: &mut [[f64; 24]; 24], sys: &System) -> Option<[[f64; 16]; 16]> {
    let [y1, y2] = spurious_combinations(&sys.spurious)?;
    // The lead matrix of the companion and W; μ, the eigenvalue at x = i.
    let (lead, w) = (
        &sys.pencil[if sys.inverted { 0 } else { 2 }],
        &sys.companion.1,
    );
    let mu = if sys.inverted { -1.0 } else { 1.0 };
    let mut z = [[0.0; 24]; 8];
    for (k, (y, shift)) in [(y1, 0), (y1, 6), (y2, 0), (y2, 6)].into_iter().enumerate() {
        // z2ᵀ = yᵀ A, complex: (re, im).
        let mut z2 = [(0.0, 0.0); 12];
        for (j, zj) in z2.iter_mut().enumerate() {
            for e in 0..6 {
                let a = lead[(shift + e, j)];
                zj.0 += y[e] * a;
                zj.1 += y[6 + e] * a;
            }
        }
        // z1ᵀ = z2ᵀ W + μ z2ᵀ, with μ (re, im) = (0, ±1).
        for j in 0..12 {
            let (mut re, mut im) = (-mu * z2[j].1, mu * z2[j].0);
            for (i, zi) in z2.iter().enumerate() {
                re += zi.0 * w[(i, j)];
                im += zi.1 * w[(i, j)];
            }
            z[2 * k][j] = re;
            z[2 * k + 1][j] = im;
            z[2 * k][12 + j] = z2[j].0;
            z[2 * k + 1][12 + j] = z2[j].1;
        }
    }
    // Householder QR of the eight columns: their span onto the first eight coordinates.
    let reflections = qr(&mut z)?;
    // Hᵀ L H, one reflection at a time from both sides.
    let size = l.iter().flatten().fold(0.0f64, |m, x| m.max(abs(*x)));
    for h in reflections.iter().flatten() {
        h.similarity(l);
    }
    let b = l;
    let block = b[..8]
        .iter()
        .flat_map(|row| &row[8..])
        .fold(0.0f64, |m, x| m.max(abs(*x)));
    // A matrix with an entry not finite is the caller's to refuse.
    if !size.is_finite() || block.is_nan() || block > DEFLATED * size {
        return None;
    }
    Some(core::array::from_fn(|i| {
        core::array::from_fn(|j| b[8 + i][8 + j])
    }))
}

/// Two complex combinations `y` of the six equations that vanish at `x = i`, `yᵀ c = 0`,
/// as `(Re y, Im y)`, independent over the complex numbers; `None` where `c` has rank
/// below four.
fn spurious_combinations(c: &[[f64; 8]; 6]) -> Option<[[f64; 12]; 2]> {
    // yᵀ c = 0 in real terms: for each column v of c (cr + i ci), the rows
    // (cr, −ci) and (ci, cr) are orthogonal to (Re y, Im y). Their orthogonal
    // complement: the last four columns of Q in their QR.
    let mut g = [[0.0; 12]; 8];
    for v in 0..4 {
        for e in 0..6 {
            let (cr, ci) = (c[e][2 * v], c[e][2 * v + 1]);
            g[2 * v][e] = cr;
            g[2 * v][6 + e] = -ci;
            g[2 * v + 1][e] = ci;
            g[2 * v + 1][6 + e] = cr;
        }
    }
    let reflections = qr(&mut g)?;
    // Q e_j for j = 8..12: the reflections applied last to first.
    let null: [[f64; 12]; 4] = core::array::from_fn(|j| {
        let mut x = [0.0; 12];
        x[8 + j] = 1.0;
        for h in reflections.iter().rev().flatten() {
            h.apply(&mut x);
        }
        x
    });
    // i y is in the null space with y: the second y is the one of the other three
    // farthest from the complex line of the first (its projection on y and i y removed).
    let y1 = null[0];
    let iy1: [f64; 12] = core::array::from_fn(|e| if e < 6 { -y1[6 + e] } else { y1[e - 6] });
    let dot = |a: &[f64; 12], b: &[f64; 12]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let y2 = null[1..]
        .iter()
        .map(|n| {
            let (a, b) = (dot(n, &y1), dot(n, &iy1));
            core::array::from_fn(|e| n[e] - a * y1[e] - b * iy1[e])
        })
        .max_by(|a: &[f64; 12], b: &[f64; 12]| dot(a, a).total_cmp(&dot(b, b)))?;
    Some([y1, y2])
}

#[cfg(test)]
mod tests {
    use super::super::eigenvalues::eigenvalues;
    use super::super::{System, FORMULATIONS};
    use super::*;
    use crate::ik::geometry::examples::general_6r as general;
    use crate::ik::geometry::Pose;
    use crate::ik::XorShift64;

    /// The deflated matrix's sixteen eigenvalues are the companion's twenty-four but
    /// the eight at `x = ±i` (`1 / x` for a reversed pencil: `∓i`), on every regular
    /// formulation of 100 random poses; none is refused.
    #[test]
    fn takes_out_exactly_the_eight_at_plus_minus_i() {
        let g = general();
        let mut rng = XorShift64::new(1994);
        let mut checked = 0;
        for _ in 0..100 {
            let q: [f64; 6] = core::array::from_fn(|_| (2.0 * rng.next_f64() - 1.0) * 3.0);
            let pose: Pose = g.fk(&q);
            for form in FORMULATIONS {
                let Some(sys) = System::new(&g, &pose, form) else {
                    continue;
                };
                let l = sys.companion_matrix();
                let mut small = deflated(&mut l.clone(), &sys).expect("deflated");
                let other = eigenvalues(&mut small, 480).expect("converges");
                let all = eigenvalues(&mut l.clone(), 720).expect("converges");
                let size = all.iter().map(|z| z.0.hypot(z.1)).fold(1.0, f64::max);
                // Each of the sixteen matched to one of the twenty-four, once.
                let mut used = [false; 24];
                for z in other {
                    let (k, d) = (0..24)
                        .filter(|&k| !used[k])
                        .map(|k| (k, (all[k].0 - z.0).hypot(all[k].1 - z.1)))
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .unwrap();
                    assert!(d <= 1e-7 * size, "{z:?} not among {all:?}");
                    used[k] = true;
                }
                // The eight left over are ±i.
                for (k, z) in all.iter().enumerate().filter(|(k, _)| !used[*k]) {
                    let d = z.0.hypot(abs(z.1) - 1.0);
                    assert!(d <= 1e-6, "left over {k}: {z:?}");
                }
                checked += 1;
            }
        }
        assert!(checked >= 100, "{checked}");
    }

    /// A matrix the eight are not eigenvalues of (the companion with one entry moved
    /// by 1e-6 of its size) is refused: the block that must vanish does not.
    #[test]
    fn refuses_a_matrix_it_does_not_deflate() {
        let g = general();
        let pose: Pose = g.fk(&[0.3, -0.7, 0.4, 1.1, -0.5, 0.8]);
        let sys = FORMULATIONS
            .iter()
            .find_map(|&form| System::new(&g, &pose, form))
            .expect("a regular formulation");
        let mut l = sys.companion_matrix();
        assert!(deflated(&mut l.clone(), &sys).is_some());
        let size = l.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        l[17][5] += 1e-6 * size;
        // Refused, and left similar: the same eigenvalues as before the call.
        let before = eigenvalues(&mut l.clone(), 720).expect("converges");
        assert!(deflated(&mut l, &sys).is_none());
        let after = eigenvalues(&mut l, 720).expect("converges");
        let scale = before.iter().map(|z| z.0.hypot(z.1)).fold(1.0, f64::max);
        let mut used = [false; 24];
        for z in after {
            let k = (0..24)
                .filter(|&k| !used[k])
                .min_by(|&a, &b| {
                    let d = |k: usize| (before[k].0 - z.0).hypot(before[k].1 - z.1);
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            let d = (before[k].0 - z.0).hypot(before[k].1 - z.1);
            assert!(d <= 1e-9 * scale, "{z:?} not among {before:?}");
            used[k] = true;
        }
    }
}
