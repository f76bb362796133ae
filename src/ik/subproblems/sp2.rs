//! **SP2** — `(θ1, θ2)` with `rot(k1, θ1) p1 = rot(k2, θ2) p2`: where the circles of `p1`
//! about `k1` and of `p2` about `k2` meet. The meeting point from the two axes, then each
//! angle by SP1; on one axis (`k2 = ±k1`), only `θ1 ∓ θ2` is fixed.
//!
//! Its forms: one pair of vectors ([`sp2`]), and the branches of a level side by side —
//! one `p1`, a `p2` per lane — for a regular pose ([`Sp2Lanes`]).

use super::sp1::{sp1, sp1_angle};
use super::{Fit, EPS, MERGE_RELATIVE, ON_AXIS, ROOT_MERGE};
use crate::ik::geometry::{sqrt0, Angle, V3};
use crate::ik::lanes::{Lanes, Vectors};

/// **SP2** — `(θ1, θ2)` with `rot(k1, θ1) p1 = rot(k2, θ2) p2`: where the circles of `p1`
/// about `k1` and of `p2` about `k2` meet. Up to two pairs; a double root when the circles
/// touch (or their two meeting points are within rounding of the data upstream, as for
/// SP3 and SP4: closer than `2√1e-11 ≈ 6e-6` of `‖p‖`, and than `6e-5` rad on the smaller
/// circle — else two roots, checked against `fk`); least squares when they miss (or
/// `‖p1‖ ≠ ‖p2‖`); `θ1` or `θ2` free (the caller's value) when its vector lies on its
/// axis. When the axes are one (`k2 = ±k1`: a 7-joint arm's locked joint can line them
/// up), only `θ1 ∓ θ2` is fixed: `θ1` is free and `θ2` follows (one pair, [`Fit::Free`]).
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
    if nn <= ON_AXIS {
        return one_axis(p1, p2, k1, c12.signum(), free);
    }
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
    // |z± − base|² = g2 nn, and z+ − z− (along n, in both circles' planes) spans
    // 2√(g2 nn) / ρ radians of the circle of radius ρ. A double root: within rounding of
    // the terms, or within MERGE_RELATIVE of ‖p‖² (errors upstream blur a double root
    // more than its own terms) — unless that is two roots well apart on the smaller
    // circle (SMALL_CIRCLE). A negative discriminant within the blur is a tangency; two
    // roots within it are checked against `fk`.
    let rho2 = (r1 - a1 * a1).min(r2 - a2 * a2).max(0.0);
    let spread = g2.abs() * nn;
    let blurred = spread <= MERGE_RELATIVE * rr;
    let double = spread <= ROOT_MERGE * EPS * terms
        || (blurred && (g2 < 0.0 || spread <= SMALL_CIRCLE * rho2));
    let zs: ([V3; 2], usize) = if double {
        fit = fit.and(Fit::Double);
        ([base, base], 1)
    } else if g2 < 0.0 {
        fit = Fit::LeastSquares;
        ([base, base], 1)
    } else {
        if blurred {
            fit = fit.and(Fit::Checked);
        }
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

/// Two meeting points within [`MERGE_RELATIVE`] of `‖p‖²` are one double root only if
/// they are also closer than `2√SMALL_CIRCLE ≈ 6e-5` rad on the smaller circle (`g2 nn ≤
/// SMALL_CIRCLE ρ²`). On a small circle (a vector near its axis: the iiwa's straight elbow
/// read from the tool, ρ = 1.3e-4 m against ‖p‖ = 0.8 m) the ‖p‖ measure alone merged
/// roots 0.028 rad apart (g2 nn / ρ² = 1.1e-4) into one branch 1.2e-8 off the pose; a
/// double root blurred upstream (the Panda with joint 7 locked at q5 = −π/2) showed
/// g2 nn / ρ² = 1.3e-11.
const SMALL_CIRCLE: f64 = 1e-9;

/// [`sp2`]'s meeting points for one `p1` and `L` vectors `p2` side by side, for a regular
/// pose (the angles are SP1's from each point, left to the caller's batch of `atan2`).
/// `M = 2 L` points: lanes `2i` and `2i + 1` are lane `i`'s two, in [`sp2`]'s order;
/// where lane `i`'s circles miss (`exact[i]` false), its one least-squares point in
/// both. The same arithmetic as [`sp2`], lane by lane.
#[derive(Clone, Copy, Debug)]
pub struct Sp2Lanes<const L: usize, const M: usize> {
    /// The meeting points `z`, with `rot(k1, θ1) p1 = z = rot(k2, θ2) p2`.
    pub z: Vectors<M>,
    /// Lanes whose circles meet in two points (the others: least squares).
    pub exact: [bool; L],
}

impl<const L: usize, const M: usize> Sp2Lanes<L, M> {
    /// `None` where some lane is not regular: the axes are one line, the circles touch
    /// (their meeting points within [`sp2`]'s merge distance of `‖p‖`, where it gives a
    /// double root or two roots checked against `fk`), or `‖p1‖ ≠ ‖p2‖` (which [`sp2`]
    /// solves in least squares: the caller's data upstream was not exact). `M` must be
    /// `2 L`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn solve(p1: &V3, p2: &Vectors<L>, k1: &V3, k2: &V3) -> Option<Self> {
        debug_assert!(M == 2 * L);
        let c12 = k1.dot(k2);
        let n = k1.cross(k2);
        let nn = n.norm_squared();
        if nn <= ON_AXIS {
            return None;
        }
        let (a1, a2) = (k1.dot(p1), p2.dot_fixed(k2));
        let alpha = (Lanes::splat(a1) - a2 * c12) / nn;
        let beta = (a2 - c12 * a1) / nn;
        let r1 = p1.norm_squared();
        let r2 = p2.dot(p2);
        let rr = (r2 + r1) * 0.5;
        let ab = alpha * beta * c12;
        let g2 = (rr - alpha * alpha - beta * beta - ab * 2.0) / nn;
        let terms = rr + alpha * alpha + beta * beta + ab.map(f64::abs) * 2.0;
        let mut exact = [true; L];
        for (i, exact) in exact.iter_mut().enumerate() {
            let double =
                g2.0[i].abs() * nn <= (ROOT_MERGE * EPS * terms.0[i]).max(MERGE_RELATIVE * rr.0[i]);
            // False for a NaN too: not regular.
            let same_length = (r1 - r2.0[i]).abs() <= 1e-9 * (r1 + r2.0[i]);
            if double || !same_length || g2.0[i].is_nan() {
                return None;
            }
            *exact = g2.0[i] >= 0.0;
        }
        let g = g2.map(sqrt0);
        let base = Vectors::splat(k1) * alpha + Vectors::splat(k2) * beta;
        let z = base.twice::<M>() + Vectors::splat(&n) * Lanes::interleave(g, -g);
        Some(Sp2Lanes { z, exact })
    }
}

/// SP2 on one axis, `k2 = σ k1`: `rot(k1, θ1 − σ θ2) p1 = p2`, so SP1 gives `θ1 − σ θ2`;
/// `θ1` takes the caller's value (free) and `θ2 = σ (θ1 − φ)`.
fn one_axis(
    p1: &V3,
    p2: &V3,
    k1: &V3,
    sigma: f64,
    free: (f64, f64),
) -> ([(Angle, Angle); 2], usize, Fit) {
    let (phi, f) = sp1(p1, p2, k1, 0.0);
    let t1 = Angle::new(free.0);
    let t2 = if f == Fit::Free {
        Angle::new(free.1)
    } else {
        Angle::new(super::wrap(sigma * (free.0 - phi)))
    };
    // Free dominates least squares in `Fit::and`'s order only when SP1 fitted.
    let fit = if f == Fit::LeastSquares {
        Fit::LeastSquares
    } else {
        Fit::Free
    };
    ([(t1, t2); 2], 1, fit)
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

    /// Two roots 0.028 rad apart on a small circle (ρ = 1e-4 of ‖p‖ = 0.8: a vector near
    /// its axis) are two roots, not one double root: their meeting points are 2.8e-6
    /// apart, within the merge distance of ‖p‖ but not of ρ. Both solve the equation.
    #[test]
    fn sp2_keeps_two_roots_close_on_a_small_circle() {
        let (k1, k2) = (V3::x(), V3::z());
        use crate::math::{sin_cos, sqrt};
        let (rho, h, phi) = (1e-4, 0.8, 0.014_f64);
        let (sin_phi, cos_phi) = sin_cos(phi);
        // Circle of p2 about z: z = h, radius ρ; of p1 about x: x = ρ cos φ, through
        // (ρ cos φ, ±ρ sin φ, h).
        let p2 = V3::new(rho, 0.0, h);
        let a = rho * cos_phi;
        let p1 = V3::new(a, 0.0, sqrt(rho * rho * sin_phi * sin_phi + h * h));
        let (pairs, n, fit) = sp2(&p1, &p2, &k1, &k2, (0.0, 0.0));
        assert_eq!(n, 2, "{pairs:?} {fit:?}");
        assert!(fit <= Fit::Checked, "{fit:?}");
        let mut t2 = [pairs[0].1.theta, pairs[1].1.theta];
        t2.sort_by(f64::total_cmp);
        assert!(
            (t2[0] + phi).abs() < 1e-6 && (t2[1] - phi).abs() < 1e-6,
            "{t2:?}"
        );
        for (t1, t2) in &pairs[..n] {
            assert!((t1.rot(&k1) * p1 - t2.rot(&k2) * p2).norm() < 1e-12);
        }
    }

    /// The lanes give [`sp2`]'s meeting points (its angles' SP1 from each), in its
    /// order, and its least-squares point where the circles miss.
    #[test]
    fn sp2_lanes_meet_the_circles_as_sp2_does() {
        use super::super::sp1::sp1_sides;
        use super::super::wrap;
        let (k1, k2) = (unit(0.0, 0.0, 1.0), unit(0.3, 1.0, 0.0));
        let p1 = V3::new(0.2, -0.4, 0.7);
        // Two p2 of p1's length: one whose circle meets p1's, one that misses it.
        let meets = rot(&k2, -0.9) * rot(&k1, 0.4) * p1;
        // (Its circle about k2 keeps |z| ≤ 0.26, p1's about z has z = 0.7.)
        let misses = (k2 * 0.9 + V3::z() * 0.3).normalize() * p1.norm();
        let p2 = Vectors {
            x: Lanes([meets.x, misses.x]),
            y: Lanes([meets.y, misses.y]),
            z: Lanes([meets.z, misses.z]),
        };
        let lanes = Sp2Lanes::<2, 4>::solve(&p1, &p2, &k1, &k2).expect("regular");
        assert_eq!(lanes.exact, [true, false]);
        for (i, p2) in [meets, misses].iter().enumerate() {
            let (pairs, n, fit) = sp2(&p1, p2, &k1, &k2, (0.0, 0.0));
            assert_eq!((n, fit == Fit::Exact), (2 - i, i == 0));
            for (r, (t1, t2)) in pairs[..n].iter().enumerate() {
                let l = 2 * i + r;
                let z = V3::new(lanes.z.x.0[l], lanes.z.y.0[l], lanes.z.z.0[l]);
                for (p, k, t) in [(&p1, &k1, t1), (p2, &k2, t2)] {
                    let (y, x, _) = sp1_sides(p, &z, k).expect("off the axis");
                    assert!(wrap(libm::atan2(y, x) - t.theta).abs() < 1e-14);
                }
            }
        }
        // Circles that touch are not regular.
        let touch = rot(&k2, -0.9) * rot(&k1, 0.4) * (k1 * p1.norm());
        let p2 = Vectors {
            x: Lanes([touch.x]),
            y: Lanes([touch.y]),
            z: Lanes([touch.z]),
        };
        assert!(Sp2Lanes::<1, 2>::solve(&(k1 * p1.norm()), &p2, &k1, &k2).is_none());
    }

    #[test]
    fn sp2_on_one_axis_takes_the_first_angle_free() {
        let k = unit(0.2, -0.5, 1.0);
        let p2 = V3::new(0.2, -0.4, 0.7);
        for sigma in [1.0, -1.0] {
            // rot(k, 0.3) p1 = rot(σk, 0.9) p2.
            let p1 = rot(&k, -0.3) * rot(&(k * sigma), 0.9) * p2;
            let (pairs, n, fit) = sp2(&p1, &p2, &k, &(k * sigma), (1.1, 0.0));
            assert_eq!((n, fit), (1, Fit::Free));
            let (t1, t2) = pairs[0];
            assert_eq!(t1.theta, 1.1);
            assert!((t1.rot(&k) * p1 - t2.rot(&(k * sigma)) * p2).norm() < 1e-13);
            assert!(t1.theta.is_finite() && t2.theta.is_finite());
        }
    }

    #[test]
    fn sp2_merges_meeting_points_closer_than_the_relative_bound() {
        // Circles that touch at (0.6, 0, 0.8) — p1's about z, p2's about x — with p2
        // blurred by 1e-12: apart by ~1e-6 of ‖p‖, far above the terms' own rounding.
        let (k1, k2) = (unit(0.0, 0.0, 1.0), unit(1.0, 0.0, 0.0));
        let p1 = V3::new(0.6, 0.0, 0.8);
        for blur in [1e-12, -1e-12] {
            let p2 = V3::new(0.6, 0.0, 0.8 + blur);
            let (pairs, n, fit) = sp2(&p1, &p2, &k1, &k2, (0.0, 0.0));
            assert_eq!((n, fit), (1, Fit::Double), "{blur}");
            assert!(pairs[0].0.theta.abs() < 1e-5 && pairs[0].1.theta.abs() < 1e-5);
        }
    }
}
