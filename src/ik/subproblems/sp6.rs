//! **SP6** — `(θ1, θ2)` with
//!
//! `h1ᵀ rot(k1, θ1) p1 + h2ᵀ rot(k2, θ2) p2 = d1`,
//! `h3ᵀ rot(k3, θ1) p3 + h4ᵀ rot(k4, θ2) p4 = d2`
//!
//! (IK-Geo's statement): two pairs of rotations. Each term is a sinusoid of its angle
//! (SP4's circle terms, `hᵀ rot(k, θ) p = a cos θ + a' sin θ + axial`), so with `u =
//! (cos θ1, sin θ1)` and `v = (cos θ2, sin θ2)` the equations are linear, `A u + B v = e`
//! ([`two_sinusoids`]). The angle whose matrix is the better conditioned is eliminated:
//! `det A · u = adj A (e − B v)`, and `‖u‖ = 1` is a trigonometric quadratic in θ2
//! (`quartic.rs`): up to four solutions. Where both `A` and `B` are singular the equations
//! do not determine the angles this way (a chain the engine does not hand to SP6); the
//! roots found are then whatever the quartic gives, and the callers' `fk` check decides.

use super::quartic::TrigQuadratic;
use super::sp4::Sp4Circle;
use super::{Fit, FourRoots};
use crate::ik::geometry::{Angle, V3};

/// Up to four solutions `(θ1, θ2)` of SP6, each with how it fits (see
/// [`QuarticRoots`](super::QuarticRoots)).
pub type Sp6Roots = FourRoots<(Angle, Angle)>;

/// **SP6** — `(θ1, θ2)` with `h1ᵀ rot(k1, θ1) p1 + h2ᵀ rot(k2, θ2) p2 = d1` and
/// `h3ᵀ rot(k3, θ1) p3 + h4ᵀ rot(k4, θ2) p4 = d2`: up to four solutions.
pub fn sp6(h: [V3; 4], k: [V3; 4], p: [V3; 4], d: [f64; 2]) -> Sp6Roots {
    let t: [Sp4Circle; 4] = core::array::from_fn(|i| Sp4Circle::terms(&h[i], &p[i], &k[i]));
    two_sinusoids(
        [[t[0].ca, t[0].sa], [t[2].ca, t[2].sa]],
        [[t[1].ca, t[1].sa], [t[3].ca, t[3].sa]],
        [
            d[0] - t[0].axial - t[1].axial,
            d[1] - t[2].axial - t[3].axial,
        ],
    )
}

/// `(θ1, θ2)` with `A u + B v = e` for `u = (cos θ1, sin θ1)`, `v = (cos θ2, sin θ2)`
/// (`a`, `b` row by row).
pub fn two_sinusoids(a: [[f64; 2]; 2], b: [[f64; 2]; 2], e: [f64; 2]) -> Sp6Roots {
    let det = |m: &[[f64; 2]; 2]| m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let mut out = Sp6Roots::empty((Angle::new(0.0), Angle::new(0.0)));
    // Row scaling multiplies both determinants alike: compare them as they are.
    let swap = det(&b).abs() > det(&a).abs();
    let (a, b) = if swap { (b, a) } else { (a, b) };
    let d = det(&a);
    // adj A = [[a11, −a01], [−a10, a00]]: d u = m − M v with m = adj A e, M = adj A B.
    let adj = |x: [f64; 2]| {
        [
            a[1][1] * x[0] - a[0][1] * x[1],
            a[0][0] * x[1] - a[1][0] * x[0],
        ]
    };
    let m = adj(e);
    let m1 = adj([b[0][0], b[1][0]]);
    let m2 = adj([b[0][1], b[1][1]]);
    let dot = |x: [f64; 2], y: [f64; 2]| x[0] * y[0] + x[1] * y[1];
    let (n1, n2) = (dot(m1, m1), dot(m2, m2));
    // ‖m − M1 cos θ − M2 sin θ‖² = d²
    let q = TrigQuadratic {
        c0: dot(m, m) + 0.5 * (n1 + n2) - d * d,
        c1: -2.0 * dot(m, m1),
        s1: -2.0 * dot(m, m2),
        c2: 0.5 * (n1 - n2),
        s2: dot(m1, m2),
    };
    let sign = if d < 0.0 { -1.0 } else { 1.0 };
    for (v, fit) in q.roots().iter() {
        let w = [
            m[0] - m1[0] * v.cos - m2[0] * v.sin,
            m[1] - m1[1] * v.cos - m2[1] * v.sin,
        ];
        if w[0] == 0.0 && w[1] == 0.0 {
            continue;
        }
        let u = Angle::atan2(sign * w[1], sign * w[0]);
        let (u, v, fit) = match refine(&a, &b, &e, u, v) {
            (u, v, true) => (u, v, fit),
            // A root Newton would move by more than rounding's reach is off the equations:
            // the quartic split a double root (its coefficients' rounding, amplified
            // there, 1e-2 apart at a wrist singularity of a three-parallel arm). It is
            // brought onto the equations by damped Gauss–Newton, where the double root's
            // Jacobian is singular, and flagged so; both halves land on it, within 1e-6
            // (the linear convergence's reach): one is kept.
            (u, v, false) => {
                let (u, v) = descend(&a, &b, &e, u, v);
                let near = |x: &Angle, y: &Angle| super::wrap(x.theta - y.theta).abs() <= 1e-6;
                let (x, y) = if swap { (v, u) } else { (u, v) };
                if out
                    .as_slice()
                    .iter()
                    .any(|(p, q)| near(p, &x) && near(q, &y))
                {
                    continue;
                }
                (u, v, fit.and(Fit::Double))
            }
        };
        out.push(if swap { (v, u) } else { (u, v) }, fit);
    }
    out
}

/// `(u, v)` moved by Newton steps on `A u + B v = e` itself: the quartic's coefficients
/// are products of the data, with cancellation, so its roots carry more rounding than the
/// equations allow. Skipped where the equations' Jacobian is near singular (a double root:
/// the quartic already placed it at its derivative's root). `false` with the root as it
/// was where a step would be beyond rounding's reach (the root is not the equations').
fn refine(
    a: &[[f64; 2]; 2],
    b: &[[f64; 2]; 2],
    e: &[f64; 2],
    mut u: Angle,
    mut v: Angle,
) -> (Angle, Angle, bool) {
    let size = |m: &[[f64; 2]; 2]| m.iter().flatten().fold(0.0f64, |x, y| x.max(y.abs()));
    let scale = size(a) * size(b);
    for _ in 0..2 {
        let (r, j) = (residual(a, b, e, &u, &v), jacobian(a, b, &u, &v));
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.is_nan() || det.abs() <= 1e-6 * scale {
            break;
        }
        let du = -(j[1][1] * r[0] - j[0][1] * r[1]) / det;
        let dv = -(j[0][0] * r[1] - j[1][0] * r[0]) / det;
        // A refinement, not a search: steps beyond rounding's reach are not taken.
        if !(du.abs() < 1e-6 && dv.abs() < 1e-6) {
            return (u, v, false);
        }
        (u, v) = (turned(u, du), turned(v, dv));
    }
    (u, v, true)
}

/// `(u, v)` brought onto `A u + B v = e` by damped Gauss–Newton steps (at a double root
/// the equations' Jacobian is singular and the convergence linear: 60 rounds take an
/// error of 1e-2 below rounding); the best iterate is kept.
fn descend(
    a: &[[f64; 2]; 2],
    b: &[[f64; 2]; 2],
    e: &[f64; 2],
    mut u: Angle,
    mut v: Angle,
) -> (Angle, Angle) {
    let miss = |u: &Angle, v: &Angle| {
        let r = residual(a, b, e, u, v);
        r[0].abs().max(r[1].abs())
    };
    let (mut best, mut best_miss) = ((u, v), miss(&u, &v));
    for _ in 0..60 {
        let (r, j) = (residual(a, b, e, &u, &v), jacobian(a, b, &u, &v));
        // (JᵀJ + λ) δ = −Jᵀ r
        let jtj = [
            [
                j[0][0] * j[0][0] + j[1][0] * j[1][0],
                j[0][0] * j[0][1] + j[1][0] * j[1][1],
            ],
            [0.0, j[0][1] * j[0][1] + j[1][1] * j[1][1]],
        ];
        let damping = 1e-14 * (jtj[0][0] + jtj[1][1]);
        let (p, q, s) = (jtj[0][0] + damping, jtj[0][1], jtj[1][1] + damping);
        let g = [
            -(j[0][0] * r[0] + j[1][0] * r[1]),
            -(j[0][1] * r[0] + j[1][1] * r[1]),
        ];
        let det = p * s - q * q;
        // (NaN included: a step from it would be no step.)
        if det.is_nan() || det <= 0.0 {
            break;
        }
        let du = (s * g[0] - q * g[1]) / det;
        let dv = (p * g[1] - q * g[0]) / det;
        (u, v) = (
            Angle::new(super::wrap(u.theta + du)),
            Angle::new(super::wrap(v.theta + dv)),
        );
        let m = miss(&u, &v);
        if m < best_miss {
            (best, best_miss) = ((u, v), m);
        } else if m.is_nan() || m > 2.0 * best_miss {
            break;
        }
    }
    best
}

/// `A u + B v − e`, `u`, `v` the angles' (cos, sin).
#[inline]
fn residual(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2], e: &[f64; 2], u: &Angle, v: &Angle) -> [f64; 2] {
    let f = |m: &[[f64; 2]; 2], k: usize, t: &Angle| m[k][0] * t.cos + m[k][1] * t.sin;
    [
        f(a, 0, u) + f(b, 0, v) - e[0],
        f(a, 1, u) + f(b, 1, v) - e[1],
    ]
}

/// The derivatives of [`residual`] by the two angles, row by row.
#[inline]
fn jacobian(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2], u: &Angle, v: &Angle) -> [[f64; 2]; 2] {
    let df = |m: &[[f64; 2]; 2], k: usize, t: &Angle| m[k][1] * t.cos - m[k][0] * t.sin;
    [[df(a, 0, u), df(b, 0, v)], [df(a, 1, u), df(b, 1, v)]]
}

/// `t + d` for a small `d` (|d| < 1e-6: `sin d = d`, `cos d = 1 − d²/2` to rounding).
fn turned(t: Angle, d: f64) -> Angle {
    let (s, c) = (d, 1.0 - 0.5 * d * d);
    Angle {
        theta: super::wrap(t.theta + d),
        sin: t.sin * c + t.cos * s,
        cos: t.cos * c - t.sin * s,
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::super::wrap;
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp6_recovers_the_generating_angles() {
        let h = [
            unit(0.2, 0.9, -0.3),
            unit(-0.5, 0.1, 0.8),
            unit(0.7, -0.2, 0.4),
            unit(0.1, 0.3, 0.9),
        ];
        let k = [
            unit(1.0, 0.2, 0.1),
            unit(-0.3, 1.0, 0.2),
            unit(1.0, 0.2, 0.1),
            unit(-0.3, 1.0, 0.2),
        ];
        let p = [
            V3::new(0.3, -0.8, 0.5),
            V3::new(1.1, 0.2, -0.4),
            V3::new(-0.6, 0.4, 0.9),
            V3::new(0.2, 0.7, 0.3),
        ];
        for (t1, t2) in [(0.4, -1.2), (2.9, 0.1), (-3.0, 3.1), (0.0, 0.0)] {
            let d = [
                h[0].dot(&(rot(&k[0], t1) * p[0])) + h[1].dot(&(rot(&k[1], t2) * p[1])),
                h[2].dot(&(rot(&k[2], t1) * p[2])) + h[3].dot(&(rot(&k[3], t2) * p[3])),
            ];
            let r = sp6(h, k, p, d);
            assert!(!r.is_empty());
            for ((a1, a2), _) in r.iter() {
                let e1 = h[0].dot(&(a1.rot(&k[0]) * p[0])) + h[1].dot(&(a2.rot(&k[1]) * p[1]));
                let e2 = h[2].dot(&(a1.rot(&k[2]) * p[2])) + h[3].dot(&(a2.rot(&k[3]) * p[3]));
                assert!((e1 - d[0]).abs() < 1e-12 && (e2 - d[1]).abs() < 1e-12);
            }
            assert!(
                r.iter()
                    .any(|((a1, a2), _)| wrap(a1.theta - t1).abs() < 1e-10
                        && wrap(a2.theta - t2).abs() < 1e-10),
                "({t1}, {t2}) not among {r:?}"
            );
        }
    }
}
