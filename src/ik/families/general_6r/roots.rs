//! Steps 4 and 5 of the general 6R: the real eigenvalues of the pencil's companion
//! matrix (Francis's QR, eigenvalues only, bounded sweeps), and for each the joints — the
//! null vector of the 12 × 12 matrix (two where two solutions share the eigen joint's
//! value), the ratios of its monomials, the two-joint side from the triangular factor.

use super::eigenvalues::eigenvalues;
use super::elimination::{System, OFFSETS};
use super::spurious::deflated;
use crate::ik::subproblems::wrap;
use crate::math::{abs, atan2, sin_cos, sqrt};
use nalgebra::{SMatrix, SVector};

/// An eigenvalue whose imaginary part is within this of its size (plus one) is real.
pub(super) const SPLIT: f64 = 1e-12;
/// Within this, real to the eigenproblem's rounding.
pub(super) const REAL: f64 = 1e-7;
/// Within this, tried as a double root split by rounding (kept if it reaches the pose).
const NEAR_REAL: f64 = 1e-3;

/// Francis double-shift sweeps allowed for the 24 × 24 companion matrix: ~2 per
/// eigenvalue converge; far more means an input it does not converge on (no solutions
/// then, never a hang).
const SWEEPS: usize = 30 * 24;
/// The same for the 16 × 16 matrix left when the spurious eight are taken out.
const SWEEPS_DEFLATED: usize = 30 * 16;

impl System {
    /// The real eigenvalues of the pencil (step 4), and the complex ones within
    /// [`NEAR_REAL`] of the real line, into `roots`, each with its imaginary part relative
    /// to its size; how many.
    pub(super) fn real_roots(&self, roots: &mut [(f64, f64); 24]) -> usize {
        let mut companion = self.companion_matrix();
        // The eight eigenvalues every pencil has at x = ±i taken out first where they
        // can be (`spurious.rs`); else — or where the QR of the sixteen does not converge
        // — all 24, of the matrix it left similar.
        let mut values = [(0.0, 0.0); 24];
        let sixteen = deflated(&mut companion, self)
            .and_then(|mut other| eigenvalues(&mut other, SWEEPS_DEFLATED));
        let count = match sixteen {
            Some(v) => {
                values[..16].copy_from_slice(&v);
                16
            }
            None => match eigenvalues(&mut companion, SWEEPS) {
                Some(v) => {
                    values = v;
                    24
                }
                None => return 0,
            },
        };
        let mut n = 0;
        for &(re, im) in &values[..count] {
            let size = sqrt(re * re + im * im);
            // Real to rounding of the eigenvalue's size, or near it: a double real root (a
            // singular pose) splits into a pair ~√ε apart, farther where the pencil is
            // ill-conditioned; such a pair is tried, and kept only if it reaches the pose.
            let im = abs(im) / (1.0 + size);
            if im <= NEAR_REAL {
                let x = if self.inverted { 1.0 / re } else { re };
                if x.is_finite() {
                    roots[n] = (x, im);
                    n += 1;
                }
            }
        }
        n
    }

    /// The companion matrix `[[0, I], [−U, −W]]` of the pencil (or of its reverse).
    pub(super) fn companion_matrix(&self) -> [[f64; 24]; 24] {
        let (u, w) = &self.companion;
        let mut companion = [[0.0; 24]; 24];
        for i in 0..12 {
            companion[i][12 + i] = 1.0;
            for j in 0..12 {
                companion[12 + i][j] = -u[(i, j)];
                companion[12 + i][12 + j] = -w[(i, j)];
            }
        }
        companion
    }

    /// Step 5: the five joints other than the eliminated one for the root `x` (the
    /// eliminated joint's slot left 0) — two configurations where `M(x)` has a null space
    /// of dimension two (two solutions sharing this joint's value, as the CRX's do), else
    /// one; and whether the null space has more dimensions than that (more solutions
    /// share the value than are read here: the CRX's two pairs at q2 = 0).
    pub(super) fn back_substitute(&self, x: f64) -> ([[f64; 6]; 2], usize, bool) {
        let qe = OFFSETS[0] + 2.0 * atan2(x, 1.0);
        // M(x) / (1 + x²): bounded as x → ∞.
        let scale = 1.0 / (1.0 + x * x);
        let [c, b, a] = &self.pencil;
        let m = (c + b * x + a * (x * x)) * scale;
        let mut out = [[0.0; 6]; 2];
        let (space, wider) = null_space(&m);
        let vectors = match space {
            NullSpace::None => return (out, 0, wider),
            NullSpace::One(v) => [v, v],
            NullSpace::Two(v1, v2) => split_pair(&v1, &v2),
        };
        let n = if vectors[0] == vectors[1] { 1 } else { 2 };
        for (slot, v) in out.iter_mut().zip(&vectors).take(n) {
            *slot = self.joints_from(qe, v);
        }
        (out, n, wider)
    }

    /// The five joints from the eigen joint's value `qe` and a monomial vector `v`.
    fn joints_from(&self, qe: f64, v: &SVector<f64, 12>) -> [f64; 6] {
        let angle = |phi: f64, ratio: (f64, f64)| wrap(phi + 2.0 * atan2(ratio.0, ratio.1));
        // v[3 i + j] ∝ xa^i xb^j: the steadiest of the ratios of neighbours.
        let (mut ra, mut rb) = ((0.0, 0.0), (0.0, 0.0));
        for i in 0..4 {
            for j in 0..3 {
                if i < 3 && weight(v[3 * (i + 1) + j], v[3 * i + j]) > weight(ra.0, ra.1) {
                    ra = (v[3 * (i + 1) + j], v[3 * i + j]);
                }
                if j < 2 && weight(v[3 * i + j + 1], v[3 * i + j]) > weight(rb.0, rb.1) {
                    rb = (v[3 * i + j + 1], v[3 * i + j]);
                }
            }
        }
        let (qa, qb) = (angle(OFFSETS[1], ra), angle(OFFSETS[2], rb));
        // The two-joint side's eight products from the triangular factor.
        let trig = |q: f64| {
            let (s, c) = sin_cos(q);
            [1.0, c, s]
        };
        let (te, ta, tb) = (trig(qe), trig(qa), trig(qb));
        let mut rhs = [0.0; 8];
        for (e, value) in rhs.iter_mut().enumerate() {
            let mut sum = 0.0;
            for (k, part) in self.left.iter().enumerate() {
                for ka in 0..3 {
                    for kb in 0..3 {
                        sum += te[k] * ta[ka] * tb[kb] * part[e][3 * ka + kb];
                    }
                }
            }
            *value = sum;
        }
        // R y + left = 0.
        let mut y = [0.0; 8];
        for i in (0..8).rev() {
            let known: f64 = (i + 1..8).map(|j| self.r[i][j] * y[j]).sum();
            y[i] = (-rhs[i] - known) / self.r[i][i];
        }
        // y[m − 1] for m = 3 k1 + k2: cos of the first at m = 3, sin at 6; the second's
        // at 1 and 2.
        let q1 = atan2(y[5], y[2]);
        let q2 = atan2(y[1], y[0]);
        let [je, ja, jb, j1, j2] = self.joints;
        let mut q = [0.0; 6];
        q[je] = wrap(qe);
        q[ja] = qa;
        q[jb] = qb;
        q[j1] = q1;
        q[j2] = q2;
        q
    }
}

/// `x² + y²`: how well a ratio `x / y` is determined by a null vector's entries.
fn weight(x: f64, y: f64) -> f64 {
    x * x + y * y
}

/// The null space of a 12 × 12 matrix with a small one: none, a vector, or two.
enum NullSpace {
    None,
    One(SVector<f64, 12>),
    Two(SVector<f64, 12>, SVector<f64, 12>),
}

/// A second pivot this small relative to the first makes the null space two-dimensional:
/// two solutions sharing the eigen joint's value give ~1e-13, two whose values are close
/// (a pose near one where they share it) anything up to this; the single null vector of
/// either would be a mixture of the two. Both vectors are tried ([`split_pair`]) and kept
/// where they reach the pose.
const SECOND_NULL: f64 = 1e-4;

/// The null space of `m` (see [`NullSpace`]) by Gaussian elimination with complete
/// pivoting: the last pivots are the smallest, their columns set free; and whether the
/// tenth pivot is as small as a second null vector's too (three or more dimensions,
/// which this reads as none or two).
fn null_space(m: &SMatrix<f64, 12, 12>) -> (NullSpace, bool) {
    let mut a = *m;
    let mut cols: [usize; 12] = core::array::from_fn(|i| i);
    let mut first = 0.0;
    let mut rank = 11;
    let mut wider = false;
    for k in 0..11 {
        let (mut bi, mut bj, mut best) = (k, k, 0.0);
        for i in k..12 {
            for j in k..12 {
                if abs(a[(i, j)]) > best {
                    (bi, bj, best) = (i, j, abs(a[(i, j)]));
                }
            }
        }
        if k == 0 {
            first = best;
        }
        wider |= k == 9 && best <= SECOND_NULL * first;
        if best == 0.0 || (k == 10 && best <= SECOND_NULL * first) {
            rank = k;
            break;
        }
        a.swap_rows(k, bi);
        a.swap_columns(k, bj);
        cols.swap(k, bj);
        for i in k + 1..12 {
            let f = a[(i, k)] / a[(k, k)];
            for j in k..12 {
                a[(i, j)] -= f * a[(k, j)];
            }
        }
    }
    if rank < 10 {
        return (NullSpace::None, true);
    }
    // Unknowns in pivot order: the free ones a unit vector each, the others by
    // back-substitution.
    let solve = |free: usize| {
        let mut y = [0.0; 12];
        y[free] = 1.0;
        for k in (0..rank).rev() {
            let mut s = 0.0;
            for j in k + 1..12 {
                s -= a[(k, j)] * y[j];
            }
            y[k] = s / a[(k, k)];
        }
        let mut v = SVector::<f64, 12>::zeros();
        for (k, &c) in cols.iter().enumerate() {
            v[c] = y[k];
        }
        let n = v.norm();
        (n.is_finite() && n > 0.0).then(|| v / n)
    };
    let space = match (rank, solve(11), solve(10)) {
        (11, Some(v), _) => NullSpace::One(v),
        (10, Some(v1), Some(v2)) => NullSpace::Two(v1, v2),
        _ => NullSpace::None,
    };
    (space, wider)
}

/// The two monomial vectors (`v[3 i + j] = xa^i xb^j`, up to scale) in the span of `v1`,
/// `v2`: shifting `i` multiplies by `xa` (`S1 v = xa S0 v`, a 2 × 2 eigenproblem, least
/// squares over the nine shifted pairs of entries); where the two share `xa` (the CRX's
/// pairs can share three joints), shifting `j` by `xb` instead. No two real solutions
/// there: `v1` and `v2` themselves.
fn split_pair(v1: &SVector<f64, 12>, v2: &SVector<f64, 12>) -> [SVector<f64, 12>; 2] {
    const ALONG_A: [(usize, usize); 9] = {
        let mut p = [(0, 0); 9];
        let mut k = 0;
        while k < 9 {
            p[k] = (k, k + 3);
            k += 1;
        }
        p
    };
    const ALONG_B: [(usize, usize); 8] = {
        let mut p = [(0, 0); 8];
        let mut k = 0;
        while k < 8 {
            let (i, j) = (k / 2, k % 2);
            p[k] = (3 * i + j, 3 * i + j + 1);
            k += 1;
        }
        p
    };
    match shift_eigenvectors(v1, v2, &ALONG_A) {
        Some((pair, apart)) if apart => pair,
        _ => shift_eigenvectors(v1, v2, &ALONG_B).map_or([*v1, *v2], |(pair, _)| pair),
    }
}

/// The eigenvectors `c` of `(S0ᵀ S0)⁻¹ S0ᵀ S1` for the shift `pairs` (`(k, k')`: entry
/// `k'` is entry `k` times the variable) on the span of `v1`, `v2`, as vectors, and whether
/// the two eigenvalues are apart; `None` when they are complex or the span degenerate.
fn shift_eigenvectors(
    v1: &SVector<f64, 12>,
    v2: &SVector<f64, 12>,
    pairs: &[(usize, usize)],
) -> Option<([SVector<f64, 12>; 2], bool)> {
    let vs = [v1, v2];
    // Gram matrices of the shifted-from (A) and shifted-to (B) rows.
    let gram = |from: bool, to: bool| {
        let mut g = [[0.0; 2]; 2];
        for (r, row) in g.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x = pairs
                    .iter()
                    .map(|&(k0, k1)| {
                        let a = if from { vs[r][k0] } else { vs[r][k1] };
                        let b = if to { vs[c][k1] } else { vs[c][k0] };
                        a * b
                    })
                    .sum();
            }
        }
        g
    };
    let (aa, ab) = (gram(true, false), gram(true, true));
    let det = |m: &[[f64; 2]; 2]| m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let d = det(&aa);
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let inv = [[aa[1][1] / d, -aa[0][1] / d], [-aa[1][0] / d, aa[0][0] / d]];
    let mut g = [[0.0; 2]; 2];
    for r in 0..2 {
        for c in 0..2 {
            g[r][c] = inv[r][0] * ab[0][c] + inv[r][1] * ab[1][c];
        }
    }
    let (tr, dt) = (g[0][0] + g[1][1], det(&g));
    let disc = tr * tr / 4.0 - dt;
    if disc < 0.0 {
        return None;
    }
    let root = sqrt(disc);
    let vec_for = |lambda: f64| {
        // (g − λ I) c = 0: c from the larger row.
        let (r0, r1) = ([g[0][0] - lambda, g[0][1]], [g[1][0], g[1][1] - lambda]);
        let row = if abs(r0[0]) + abs(r0[1]) >= abs(r1[0]) + abs(r1[1]) {
            r0
        } else {
            r1
        };
        let v = v1 * -row[1] + v2 * row[0];
        let n = v.norm();
        if n > 0.0 {
            v / n
        } else {
            *v1
        }
    };
    let apart = root > 1e-6 * (1.0 + abs(tr));
    Some(([vec_for(tr / 2.0 + root), vec_for(tr / 2.0 - root)], apart))
}
