//! Steps 1–3 of the general 6R for one pose and one [`Formulation`]: Raghavan and Roth's
//! fourteen quantities of both sides, their coefficients read off the geometry on a grid
//! of thirds of a turn, the two-joint side's eight products eliminated by Householder
//! reflections, and the six equations left written as a 12 × 12 quadratic pencil in the
//! eigen joint's half-angle tangent ([`System`]).

use super::formulation::{joint, Formulation, Link};
use crate::ik::geometry::{orthogonal, Geometry, Pose, V3};
use crate::math::{abs, sin_cos, sqrt};
use nalgebra::SMatrix;

/// Raghavan–Roth's quantities per side.
const EQS: usize = 14;
/// Equations left after the eight products of (q1, q2) are eliminated.
const LEFT: usize = EQS - 8;

/// A grid of thirds of a turn: `{1, cos θ, sin θ}` at these three angles determine the
/// coefficients of any `a + b cos θ + c sin θ` exactly (`WEIGHTS`).
const GRID_COS: [f64; 3] = [1.0, -0.5, -0.5];
const GRID_SIN: [f64; 3] = [0.0, 0.866_025_403_784_438_6, -0.866_025_403_784_438_6];
/// `WEIGHTS[k][i]`: the coefficient `k` (of 1, cos, sin) from the samples `i`.
const WEIGHTS: [[f64; 3]; 3] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0],
    [0.0, 0.577_350_269_189_625_8, -0.577_350_269_189_625_8],
];

/// Raghavan and Roth's fourteen quantities of a point `p` and a direction `l`.
#[inline]
fn fourteen(p: &V3, l: &V3) -> [f64; EQS] {
    let (pp, pl) = (p.dot(p), p.dot(l));
    let x = p.cross(l);
    let v = l * pp - p * (2.0 * pl);
    [
        p.x, p.y, p.z, l.x, l.y, l.z, pp, pl, x.x, x.y, x.z, v.x, v.y, v.z,
    ]
}

/// Which of the fourteen are vectors (turned by joint 3) — the rest, `p·p` and `p·l`,
/// are invariant.
const VECTORS: [usize; 4] = [0, 3, 8, 11];

/// Coefficients of `f(θa, θb)` on `{1, cos θa, sin θa} ⊗ {1, cos θb, sin θb}` (index `3 ka +
/// kb`) from its samples on the grid (`samples[3 i + j]` at `(θa_i, θb_j)`).
fn fourier(samples: &[[f64; EQS]; 9]) -> [[f64; 9]; EQS] {
    let mut out = [[0.0; 9]; EQS];
    for (e, row) in out.iter_mut().enumerate() {
        for ka in 0..3 {
            for kb in 0..3 {
                let mut sum = 0.0;
                for i in 0..3 {
                    for j in 0..3 {
                        sum += WEIGHTS[ka][i] * WEIGHTS[kb][j] * samples[3 * i + j][e];
                    }
                }
                row[3 * ka + kb] = sum;
            }
        }
    }
    out
}

/// `(1 + x²) {1, cos θ, sin θ}` with `θ = φ + 2 atan x`, as polynomials in `x`:
/// `HALF[power][k]` for offset `φ` given by its sine and cosine.
fn half_angle(s: f64, c: f64) -> [[f64; 3]; 3] {
    [[1.0, c, s], [0.0, -2.0 * s, 2.0 * c], [1.0, -c, -s]]
}

/// The smallest pivot ratio of the better end of a regular pencil: a degenerate
/// formulation's (or pose's) are rounding, 1e-15 to 1e-17; a regular one's were ≥ 1e-5 on
/// 3 000 poses of the Jaco.
const REGULAR: f64 = 1e-9;

/// Offsets of the half-angle parameters of q3, q4, q5: generic angles, so that no
/// solution of a pose met in practice (joints at 0 or ±π) sits at `x = ∞`.
pub(super) const OFFSETS: [f64; 3] = [0.403, -0.611, 0.257];

/// The eliminated system of one pose: what back-substitution reads.
pub(super) struct System {
    /// `left[k][e][m]`: the coefficient of `{1, cos θe, sin θe}[k] · m[m]` in equation `e`
    /// (θe the eigen joint, `m` the nine products of the three-joint side's other two),
    /// after the reflections (rows 0..8: with the triangular factor; rows 8..14: the six
    /// equations free of the two-joint side). The constant of the two-joint side is in
    /// `left[0][e][0]`.
    pub(super) left: [[[f64; 9]; EQS]; 3],
    /// The triangular factor of the two-joint side's eight products.
    pub(super) r: [[f64; 8]; 8],
    /// The quadratic pencil `A x² + B x + C` (`pencil[power]`).
    pub(super) pencil: [SMatrix<f64, 12, 12>; 3],
    /// `(A⁻¹ C, A⁻¹ B)`, or `(C⁻¹ A, C⁻¹ B)` when `inverted` (the eigenvalues are then
    /// `1 / x`): the companion matrix's lower blocks, negated.
    pub(super) companion: (SMatrix<f64, 12, 12>, SMatrix<f64, 12, 12>),
    pub(super) inverted: bool,
    /// Where the six equations stand at `x = i` (`spurious.rs`): `spurious[e][2 v]` and
    /// `[2 v + 1]`, the real and imaginary parts of the coefficient of vector quantity `v`'s
    /// component across the eigen axis in equation `e`.
    pub(super) spurious: [[f64; 8]; LEFT],
    /// The smallest over the largest pivot of the companion's lead matrix: how far the
    /// pencil is from singular.
    pub(super) ratio: f64,
    /// Joints: the eigen joint, the three-joint side's two sampled joints and the
    /// two-joint side's (each innermost first, as `sample` returns them).
    pub(super) joints: [usize; 5],
    /// The joint carried round the loop.
    pub(super) eliminated: usize,
}

/// Samples a side's links (innermost first: two turns, perhaps the fixed link) on the
/// grid of its two turns: the sampled joints (first, second) and the points and
/// directions at `samples[3 i + j]`.
fn sample(links: &[Link], start: &(V3, V3)) -> ([usize; 2], [(V3, V3); 9]) {
    let mut turns = [usize::MAX; 2];
    let mut n = 0;
    for (i, l) in links.iter().enumerate() {
        if matches!(l, Link::Turn { .. }) {
            turns[n] = i;
            n += 1;
        }
    }
    let mut out = [(V3::zeros(), V3::zeros()); 9];
    for i in 0..3 {
        for j in 0..3 {
            let (mut p, mut l) = *start;
            for (k, link) in links.iter().enumerate() {
                let g = if k == turns[0] {
                    i
                } else if k == turns[1] {
                    j
                } else {
                    0
                };
                (p, l) = link.apply(&p, &l, GRID_SIN[g], GRID_COS[g]);
            }
            out[3 * i + j] = (p, l);
        }
    }
    (turns.map(|t| joint(&links[t])), out)
}

impl System {
    /// Steps 1–3 of the module for `pose` written as `form`; `None` when the formulation
    /// is degenerate for this arm: the two-joint side's products of rank below 8, or the
    /// pencil singular.
    pub(super) fn new(g: &Geometry<6>, pose: &Pose, form: Formulation) -> Option<System> {
        let sides = form.sides(g, pose);
        let three = &sides.three[..sides.three_len];
        let two = &sides.two[..sides.two_len];
        let eigen = three.len() - 1;
        let Link::Turn {
            joint: je,
            axis: he,
            point: o,
        } = three[eigen]
        else {
            return None;
        };
        // Lengths in units of the arm's size: the fourteen mix lengths, squares and
        // directions.
        let size =
            g.p.iter()
                .chain(core::iter::once(&g.p_tool))
                .map(|p| (p - o).norm())
                .fold(0.0, f64::max);
        let unit = if size > 0.0 { 1.0 / size } else { 1.0 };
        let rel = |(p, l): &(V3, V3)| ((p - o) * unit, *l);
        // The two-joint side on its grid.
        let (two_joints, at) = sample(two, &sides.start);
        let right = fourier(&at.map(|x| {
            let (p, l) = rel(&x);
            fourteen(&p, &l)
        }));
        // The three-joint side on the grid of its inner turns, then the eigen joint's turn
        // split into its parts along the axis (1), across it (cos) and `he ×` (sin).
        let (three_joints, at) = sample(&three[..eigen], &sides.start);
        let mut parts = [[[0.0; EQS]; 9]; 3];
        for (s, x) in at.iter().enumerate() {
            let (p, l) = rel(x);
            let all = fourteen(&p, &l);
            parts[0][s] = all;
            for &v in &VECTORS {
                let w = V3::new(all[v], all[v + 1], all[v + 2]);
                let along = he * he.dot(&w);
                let (across, turned) = (w - along, he.cross(&w));
                for d in 0..3 {
                    parts[0][s][v + d] = along[d];
                    parts[1][s][v + d] = across[d];
                    parts[2][s][v + d] = turned[d];
                }
            }
        }
        let mut left = parts.map(|p| fourier(&p));
        // Both sides on the left: the right's constant, then its eight products.
        let mut products = [[0.0; 8]; EQS];
        for e in 0..EQS {
            left[0][e][0] -= right[e][0];
            for m in 0..8 {
                products[e][m] = -right[e][m + 1];
            }
        }
        // At x = i (a root of the half-angle's 1 + x²) a vector quantity's two turned
        // parts add up to a multiple of one complex vector `u + i he × u` across the
        // axis, and its invariant part is gone: `spurious.rs` reads the eight roots there
        // off these four columns, reflected with the rest.
        let (u, v) = (orthogonal(&he), he.cross(&orthogonal(&he)));
        let mut at_i = [[0.0; EQS]; 8];
        for (k, &row) in VECTORS.iter().enumerate() {
            for d in 0..3 {
                at_i[2 * k][row + d] = u[d];
                at_i[2 * k + 1][row + d] = v[d];
            }
        }
        let r = eliminate(&mut products, &mut left, &mut at_i)?;
        let spurious = core::array::from_fn(|e| core::array::from_fn(|m| at_i[m][8 + e]));
        let pencil = pencil(&left);
        // The companion of the better-conditioned end: x or 1/x (a root near x = ∞);
        // both singular, the pencil is (every x a root: a degenerate formulation).
        let [c, b, a] = &pencil;
        let (la, lc) = (a.full_piv_lu(), c.full_piv_lu());
        let (ra, rc) = (pivot_ratio(&la), pivot_ratio(&lc));
        // NaN (a non-finite pose) is not regular either.
        if ra.max(rc).is_nan() || ra.max(rc) <= REGULAR {
            return None;
        }
        let (lead, last, inverted) = if ra >= rc {
            (la, c, false)
        } else {
            (lc, a, true)
        };
        let companion = (lead.solve(last)?, lead.solve(b)?);
        Some(System {
            left,
            r,
            pencil,
            companion,
            inverted,
            spurious,
            ratio: ra.max(rc),
            joints: [
                je,
                three_joints[0],
                three_joints[1],
                two_joints[0],
                two_joints[1],
            ],
            eliminated: form.eliminated,
        })
    }
}

/// The smallest over the largest pivot of a full-pivoting LU: how far from singular.
fn pivot_ratio(lu: &nalgebra::FullPivLU<f64, nalgebra::Const<12>, nalgebra::Const<12>>) -> f64 {
    let u = lu.u();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..12 {
        lo = lo.min(abs(u[(i, i)]));
        hi = hi.max(abs(u[(i, i)]));
    }
    if hi > 0.0 {
        lo / hi
    } else {
        0.0
    }
}

/// Step 2: Householder reflections that make the eight products' coefficients upper
/// triangular, applied to the left side and to the `columns` too; the triangular factor,
/// or `None` when a pivot vanishes (rank below 8).
fn eliminate(
    products: &mut [[f64; 8]; EQS],
    left: &mut [[[f64; 9]; EQS]; 3],
    columns: &mut [[f64; EQS]; 8],
) -> Option<[[f64; 8]; 8]> {
    let scale = products
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(abs(*x)));
    for col in 0..8 {
        let norm = sqrt(
            (col..EQS)
                .map(|i| products[i][col] * products[i][col])
                .sum(),
        );
        if norm.is_nan() || norm <= 1e-12 * scale {
            return None;
        }
        let alpha = if products[col][col] > 0.0 {
            -norm
        } else {
            norm
        };
        let mut v = [0.0; EQS];
        for i in col..EQS {
            v[i] = products[i][col];
        }
        v[col] -= alpha;
        let vv: f64 = v[col..].iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        // x ← x − 2 v (vᵀ x) / (vᵀ v) on every column.
        let reflect = |x: &mut [f64; EQS]| {
            let dot: f64 = (col..EQS).map(|i| v[i] * x[i]).sum();
            let f = 2.0 * dot / vv;
            for i in col..EQS {
                x[i] -= f * v[i];
            }
        };
        for c in col..8 {
            let mut x: [f64; EQS] = core::array::from_fn(|i| products[i][c]);
            reflect(&mut x);
            for (row, xi) in products.iter_mut().zip(x) {
                row[c] = xi;
            }
        }
        for part in left.iter_mut() {
            for m in 0..9 {
                let mut x: [f64; EQS] = core::array::from_fn(|i| part[i][m]);
                reflect(&mut x);
                for (row, xi) in part.iter_mut().zip(x) {
                    row[m] = xi;
                }
            }
        }
        for x in columns.iter_mut() {
            reflect(x);
        }
    }
    let mut r = [[0.0; 8]; 8];
    for i in 0..8 {
        r[i][i..].copy_from_slice(&products[i][i..]);
    }
    Some(r)
}

/// Step 3: the six equations free of (q1, q2) as polynomials in the half-angle
/// parameters, and the 12 × 12 pencil in x3 (rows `e` and `x4 · e`, columns `x4^i x5^j`
/// at `3 i + j`).
fn pencil(left: &[[[f64; 9]; EQS]; 3]) -> [SMatrix<f64, 12, 12>; 3] {
    let [h3, h4, h5] = OFFSETS.map(|phi| {
        let (s, c) = sin_cos(phi);
        half_angle(s, c)
    });
    let mut out = [SMatrix::<f64, 12, 12>::zeros(); 3];
    for e in 0..LEFT {
        // The three half-angle substitutions one variable at a time: `t[k3][k4][k5]` →
        // `[i3][i4][i5]`.
        let mut t = [[[0.0; 3]; 3]; 3];
        for (k3, part) in left.iter().enumerate() {
            for k4 in 0..3 {
                for k5 in 0..3 {
                    t[k3][k4][k5] = part[8 + e][3 * k4 + k5];
                }
            }
        }
        let x = along(&h5, &along(&h4, &along(&h3, &t, 0), 1), 2);
        for (i3, m) in out.iter_mut().enumerate() {
            for i4 in 0..3 {
                for i5 in 0..3 {
                    m[(e, 3 * i4 + i5)] = x[i3][i4][i5];
                    m[(LEFT + e, 3 * (i4 + 1) + i5)] = x[i3][i4][i5];
                }
            }
        }
    }
    out
}

/// `t` with the matrix `h` applied along its index `axis` (0, 1 or 2): one variable's
/// half-angle substitution.
fn along(h: &[[f64; 3]; 3], t: &[[[f64; 3]; 3]; 3], axis: usize) -> [[[f64; 3]; 3]; 3] {
    let mut out = [[[0.0; 3]; 3]; 3];
    for (a, plane) in out.iter_mut().enumerate() {
        for (b, row) in plane.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                // Written out per axis: a generic index juggling cost about nine times as much.
                *x = match axis {
                    0 => h[a][0] * t[0][b][c] + h[a][1] * t[1][b][c] + h[a][2] * t[2][b][c],
                    1 => h[b][0] * t[a][0][c] + h[b][1] * t[a][1][c] + h[b][2] * t[a][2][c],
                    _ => h[c][0] * t[a][b][0] + h[c][1] * t[a][b][1] + h[c][2] * t[a][b][2],
                };
            }
        }
    }
    out
}
