//! **SP2** — `(θ1, θ2)` with `rot(k1, θ1) p1 = rot(k2, θ2) p2`: where the circles of `p1`
//! about `k1` and of `p2` about `k2` meet (`k1 ∦ k2`). The meeting point from the two
//! axes, then each angle by SP1.

use super::sp1::sp1_angle;
use super::{Fit, EPS, ROOT_MERGE};
use crate::ik::geometry::{sqrt0, Angle, V3};

/// **SP2** — `(θ1, θ2)` with `rot(k1, θ1) p1 = rot(k2, θ2) p2`: where the circles of `p1`
/// about `k1` and of `p2` about `k2` meet (`k1 ∦ k2`). Up to two pairs; a double root when
/// the circles touch; least squares when they miss (or `‖p1‖ ≠ ‖p2‖`); `θ1` or `θ2` free
/// (the caller's value) when its vector lies on its axis.
pub fn sp2(
    p1: &V3,
    p2: &V3,
    k1: &V3,
    k2: &V3,
    free: (f64, f64),
) -> ([(Angle, Angle); 2], usize, Fit) {
    // The meeting point z = α k1 + β k2 + γ (k1 × k2): kᵢ·z = kᵢ·pᵢ, ‖z‖ = ‖p1‖.
    let c12 = k1.dot(k2);
    let n = k1.cross(k2);
    let nn = n.norm_squared();
    let (a1, a2) = (k1.dot(p1), k2.dot(p2));
    let alpha = (a1 - c12 * a2) / nn;
    let beta = (a2 - c12 * a1) / nn;
    let r1 = p1.norm_squared();
    let r2 = p2.norm_squared();
    let mut fit = if (r1 - r2).abs() <= 1e-9 * (r1 + r2) {
        Fit::Exact
    } else {
        Fit::LeastSquares
    };
    let rr = 0.5 * (r1 + r2);
    let g2 = (rr - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12) / nn;
    let base = k1 * alpha + k2 * beta;
    let terms = rr + alpha * alpha + beta * beta + 2.0 * (alpha * beta * c12).abs();
    let zs: ([V3; 2], usize) = if g2.abs() <= ROOT_MERGE * EPS * terms / nn {
        fit = fit.and(Fit::Double);
        ([base, base], 1)
    } else if g2 < 0.0 {
        fit = Fit::LeastSquares;
        ([base, base], 1)
    } else {
        let g = n * sqrt0(g2);
        ([base + g, base - g], 2)
    };
    let zero = Angle {
        theta: 0.0,
        sin: 0.0,
        cos: 1.0,
    };
    let mut out = [(zero, zero); 2];
    for (o, z) in out.iter_mut().zip(zs.0.iter()).take(zs.1) {
        let (t1, f1) = sp1_angle(p1, z, k1, free.0);
        let (t2, f2) = sp1_angle(p2, z, k2, free.1);
        *o = (t1, t2);
        fit = fit.and(mild(f1)).and(mild(f2));
    }
    (out, zs.1, fit)
}

/// A least-squares SP1 inside a larger subproblem only reflects the outer fit (already
/// counted there); a free one is a singularity.
#[inline]
fn mild(f: Fit) -> Fit {
    match f {
        Fit::LeastSquares => Fit::Exact,
        f => f,
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp2_meets_two_circles() {
        let (k1, k2) = (unit(0.0, 0.0, 1.0), unit(0.3, 1.0, 0.0));
        let p2 = V3::new(0.2, -0.4, 0.7);
        let z = rot(&k2, 0.9) * p2;
        let p1 = rot(&k1, -0.4) * z;
        let (pairs, n, fit) = sp2(&p1, &p2, &k1, &k2, (0.0, 0.0));
        assert_eq!((n, fit), (2, Fit::Exact));
        for (t1, t2) in &pairs[..n] {
            assert!((t1.rot(&k1) * p1 - t2.rot(&k2) * p2).norm() < 1e-13);
            assert!((rot(&k1, t1.theta) - t1.rot(&k1)).norm() < 1e-15);
        }
        assert!(pairs[..n]
            .iter()
            .any(|(t1, t2)| (t1.theta - 0.4).abs() < 1e-12 && (t2.theta - 0.9).abs() < 1e-12));
    }
}
