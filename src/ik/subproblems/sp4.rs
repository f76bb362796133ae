//! **SP4** — `θ` with `hᵀ rot(k, θ) p = d`: where the circle of `p` about `k` crosses the
//! plane `hᵀ x = d`. With `rot(k, θ) p = (k·p) k + cos θ p⊥ + sin θ (k × p)` it is the
//! equation `a cos θ + a' sin θ = b` of the module (`cos_equation`), for the circle's
//! terms ([`Sp4Circle`]).
//!
//! Its forms: one plane ([`sp4`]), one circle for many planes ([`Sp4`]), the branches of a
//! level side by side ([`Sp4Lanes`]).

use super::{
    cos_case, cos_equation, roots_of, CosCase, Fit, RootLanes, Roots, EPS, MERGE_RELATIVE, ON_AXIS,
    ROOT_MERGE,
};
use crate::ik::geometry::{flat, scale, sqrt0, Angle, V3};
use crate::ik::lanes::Lanes;
use crate::math::{fast_atan2 as atan2, sqrt};

/// **SP4** — `θ` with `hᵀ rot(k, θ) p = d`: where the circle of `p` about `k` crosses the
/// plane `hᵀ x = d`. Two roots, a double root (the circle touches the plane), least
/// squares (it misses the plane), or free (the circle lies in a plane `hᵀ x = d`).
pub fn sp4(h: &V3, p: &V3, k: &V3, d: f64, free: f64) -> Roots {
    sp4_terms(h, p, k, d, d.abs(), free)
}

/// SP4 where `d` was computed from terms of size `terms` (its rounding error).
pub(super) fn sp4_terms(h: &V3, p: &V3, k: &V3, d: f64, terms: f64, free: f64) -> Roots {
    let c = Sp4Circle::terms(h, p, k);
    cos_equation(c.ca, c.sa, d - c.axial, terms, c.mag2, free, None)
}

/// What SP4 needs of `h`, `p`, `k` (`hᵀ rot(k, θ) p = ca cos θ + sa sin θ + axial`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Sp4Circle {
    pub(super) ca: f64,
    pub(super) sa: f64,
    pub(super) axial: f64,
    mag2: f64,
}

impl Sp4Circle {
    #[inline(always)]
    pub(super) fn terms(h: &V3, p: &V3, k: &V3) -> Sp4Circle {
        // rot(k, θ) p = (k·p) k + cos θ p⊥ + sin θ (k × p)
        Sp4Circle {
            ca: h.dot(&flat(k, p)),
            sa: h.dot(&k.cross(p)),
            axial: h.dot(k) * k.dot(p),
            mag2: h.norm_squared() * p.norm_squared(),
        }
    }
}

/// [`sp4`] for one `h`, `p`, `k` and many `d` (a solver's loop over the branches before
/// it): the circle's terms and its angle `φ` found once, then one `atan2` per call.
#[derive(Clone, Copy, Debug)]
pub struct Sp4 {
    circle: Sp4Circle,
    phi: Option<Angle>,
}

impl Sp4 {
    /// The circle of `p` about `k`, cut by planes `hᵀ x = d`.
    #[inline]
    pub fn new(h: &V3, p: &V3, k: &V3) -> Sp4 {
        let circle = Sp4Circle::terms(h, p, k);
        let (ca, sa) = (circle.ca, circle.sa);
        // r = 0 (checked per call against the call's scale): no angle.
        let phi = (ca * ca + sa * sa > 0.0).then(|| Angle::atan2(sa, ca));
        Sp4 { circle, phi }
    }

    /// The roots for `d`, as [`sp4`] gives them.
    #[inline]
    pub fn solve(&self, d: f64, free: f64) -> Roots {
        self.solve_terms(d, d.abs(), free)
    }

    /// The two roots `φ ± d` for `d` when the circle crosses the plane at all (`r² > b²`),
    /// without the merge of near-double roots that [`Sp4::solve`] applies: for a caller
    /// whose merged root turned out too far from its target (two roots a few µrad apart
    /// are then both real solutions, not one blurred by rounding).
    #[inline]
    pub fn split(&self, d: f64) -> Option<[Angle; 2]> {
        let c = &self.circle;
        let b = d - c.axial;
        let disc = c.ca * c.ca + c.sa * c.sa - b * b;
        let phi = self.phi?;
        (disc > 0.0).then(|| {
            let half = atan2(sqrt0(disc), b);
            roots_of(phi.theta, half).map(Angle::new)
        })
    }

    #[inline]
    pub(super) fn solve_terms(&self, d: f64, terms: f64, free: f64) -> Roots {
        let c = &self.circle;
        cos_equation(c.ca, c.sa, d - c.axial, terms, c.mag2, free, self.phi)
    }
}

/// [`Sp4`] for the branches of a level side by side: one circle `hᵀ rot(k, θ) p`, cut
/// by `L` planes at once. Its angle `φ` is left to the caller's batch of `atan2`.
#[derive(Clone, Copy, Debug)]
pub struct Sp4Lanes {
    pub(super) circle: Sp4Circle,
}

impl Sp4Lanes {
    /// The circle of `p` about `k`, cut by planes `hᵀ x = d`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn new(h: &V3, p: &V3, k: &V3) -> Sp4Lanes {
        Sp4Lanes {
            circle: Sp4Circle::terms(h, p, k),
        }
    }

    /// The circle's angle: `φ = atan2(y, x)` for `(y, x)` this.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn phi_sides(&self) -> (f64, f64) {
        (self.circle.sa, self.circle.ca)
    }

    /// [`Sp4::solve`] for `L` values of `d` (each computed from terms of size `terms`),
    /// when each has two distinct exact roots or misses the circle (see [`RootLanes`]);
    /// `None` for a double root, a circle of radius zero, or any other case the scalar
    /// solve flags singular or free.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn solve<const L: usize>(&self, d: Lanes<L>, terms: Lanes<L>) -> Option<RootLanes<L>> {
        let c = &self.circle;
        let (ca, sa) = (c.ca, c.sa);
        let rr = ca * ca + sa * sa;
        // A circle of radius zero (relative to the data, as `cos_case` decides): every θ
        // gives the same value, free or least squares.
        if rr <= ON_AXIS * scale(c.mag2) {
            return None;
        }
        let mut b = d - c.axial;
        let mut disc = Lanes::splat(rr) - b * b;
        // `cos_case`'s first bound for every lane at once: beyond it, a positive
        // discriminant is two distinct roots. A lane within it takes the scalar test.
        let bound = ((terms * terms + c.mag2) * 2.0 + 2.0 * rr) * EPS;
        let mut clear = true;
        for i in 0..L {
            clear &= disc.0[i] > (ROOT_MERGE * bound.0[i]).max(MERGE_RELATIVE * rr);
        }
        let mut exact = [true; L];
        if !clear {
            for (i, exact) in exact.iter_mut().enumerate() {
                match cos_case(rr, b.0[i], terms.0[i], c.mag2) {
                    CosCase::Two { .. } => {}
                    CosCase::One {
                        fit: Fit::LeastSquares,
                    } => {
                        // The nearest: θ = φ where b ≥ 0, else φ + π (d = 0 or π).
                        *exact = false;
                        b.0[i] = if b.0[i] >= 0.0 { 1.0 } else { -1.0 } * sqrt(rr);
                        disc.0[i] = 0.0;
                    }
                    _ => return None,
                }
            }
        }
        let sd = disc.sqrt();
        let inv = 1.0 / rr;
        Some(RootLanes {
            sin: [(b * sa + sd * ca) * inv, (b * sa - sd * ca) * inv],
            cos: [(b * ca - sd * sa) * inv, (b * ca + sd * sa) * inv],
            y: sd,
            x: b,
            exact,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::super::{sp3, wrap, Sp3};
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp4_crosses_a_plane() {
        let (h, k, p) = (
            unit(1.0, 0.2, 0.3),
            unit(0.0, 0.3, 1.0),
            V3::new(0.5, -0.1, 0.2),
        );
        let d = h.dot(&(rot(&k, -2.0) * p));
        let r = sp4(&h, &p, &k, d, 0.0);
        assert_eq!((r.n, r.fit), (2, Fit::Exact));
        assert!(r.thetas().any(|t| (t + 2.0).abs() < 1e-12));
        for a in r.as_slice() {
            assert!((h.dot(&(rot(&k, a.theta) * p)) - d).abs() < 1e-14);
            // The sine and cosine found with the root are its own.
            assert!((a.sin - a.theta.sin()).abs() < 1e-15 && (a.cos - a.theta.cos()).abs() < 1e-15);
        }
        // Out of range: the nearest, flagged.
        let r = sp4(&h, &p, &k, 10.0, 0.0);
        assert_eq!((r.n, r.fit), (1, Fit::LeastSquares));
    }

    #[test]
    fn prepared_circles_give_the_same_roots() {
        let (h, k, p) = (
            unit(1.0, 0.2, 0.3),
            unit(0.0, 0.3, 1.0),
            V3::new(0.5, -0.1, 0.2),
        );
        let c4 = Sp4::new(&h, &p, &k);
        let (p1, p2) = (V3::new(1.0, 0.2, 0.0), V3::new(3.0, -0.5, 0.1));
        let c3 = Sp3::new(&p1, &p2, &k);
        let same = |a: Roots, b: Roots| {
            assert_eq!((a.n, a.fit), (b.n, b.fit));
            for (x, y) in a.as_slice().iter().zip(b.as_slice()) {
                assert!(wrap(x.theta - y.theta).abs() < 1e-14, "{a:?} {b:?}");
                assert!((x.sin - y.sin).abs() < 1e-15 && (x.cos - y.cos).abs() < 1e-15);
            }
        };
        // Two roots, the double root at the circle's extremes, and misses on both sides.
        let r = c4.circle.ca.hypot(c4.circle.sa);
        let (top, bottom) = (c4.circle.axial + r, c4.circle.axial - r);
        assert_eq!(c4.solve(top, 0.0).fit, Fit::Double);
        assert_eq!(c4.solve(bottom, 0.0).fit, Fit::Double);
        for d in [0.1, -0.2, top, bottom, 10.0, -10.0] {
            same(c4.solve(d, 0.3), sp4(&h, &p, &k, d, 0.3));
        }
        for d in [2.5, 2.0, 1.5, 4.5, 0.1] {
            same(c3.solve(d, 0.3), sp3(&p1, &p2, &k, d, 0.3));
        }
        // A point on the axis: no circle, the free value.
        let on_axis = Sp4::new(&h, &(k * 2.0), &k);
        same(on_axis.solve(0.1, 0.3), sp4(&h, &(k * 2.0), &k, 0.1, 0.3));
    }
}
