//! **SP3** — `θ` with `‖rot(k, θ) p1 − p2‖ = d`: where the circle of `p1` about `k` meets
//! the sphere of radius `d` about `p2`. Squared, it is `p2ᵀ rot(k, θ) p1 = (‖p1‖² + ‖p2‖² −
//! d²) / 2`: SP4 (`sp4.rs`) with `h = p2`, `p = p1`.
//!
//! Its forms: one distance ([`sp3`]), one circle for many distances ([`Sp3`]), the
//! branches of a level side by side ([`Sp3Lanes`], which also tells how far a distance is
//! out of reach).

use super::sp4::{sp4_terms, Sp4, Sp4Lanes};
use super::{RootLanes, Roots};
use crate::ik::geometry::{sqrt0, V3};
use crate::ik::lanes::Lanes;
use crate::math::sqrt;

/// **SP3** — `θ` with `‖rot(k, θ) p1 − p2‖ = d`: where the circle of `p1` about `k` meets
/// the sphere of radius `d` about `p2`. Two roots, a double root, least squares (the
/// nearest distance to `d`), or free (the circle is a point, or centred on the sphere's
/// axis).
pub fn sp3(p1: &V3, p2: &V3, k: &V3, d: f64, free: f64) -> Roots {
    // ‖rot p1 − p2‖² = ‖p1‖² + ‖p2‖² − 2 p2ᵀ rot(k, θ) p1 = d²  ⇔  p2ᵀ rot p1 = (…)/2
    let (n1, n2) = (p1.norm_squared(), p2.norm_squared());
    let rhs = 0.5 * (n1 + n2 - d * d);
    sp4_terms(p2, p1, k, rhs, 0.5 * (n1 + n2 + d * d), free)
}

/// [`sp3`] for one `p1`, `p2`, `k` and many distances `d`.
#[derive(Clone, Copy, Debug)]
pub struct Sp3 {
    circle: Sp4,
    n1: f64,
    n2: f64,
}

impl Sp3 {
    /// The circle of `p1` about `k`, against spheres about `p2`.
    #[inline]
    pub fn new(p1: &V3, p2: &V3, k: &V3) -> Sp3 {
        Sp3 {
            circle: Sp4::new(p2, p1, k),
            n1: p1.norm_squared(),
            n2: p2.norm_squared(),
        }
    }

    /// The roots for `d`, as [`sp3`] gives them.
    #[inline]
    pub fn solve(&self, d: f64, free: f64) -> Roots {
        let (n1, n2) = (self.n1, self.n2);
        self.circle
            .solve_terms(0.5 * (n1 + n2 - d * d), 0.5 * (n1 + n2 + d * d), free)
    }
}

/// [`Sp3`] for the branches of a level side by side (see [`Sp4Lanes`]).
#[derive(Clone, Copy, Debug)]
pub struct Sp3Lanes {
    circle: Sp4Lanes,
    n: f64,
}

impl Sp3Lanes {
    /// The circle of `p1` about `k`, against spheres about `p2`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn new(p1: &V3, p2: &V3, k: &V3) -> Sp3Lanes {
        Sp3Lanes {
            circle: Sp4Lanes::new(p2, p1, k),
            n: p1.norm_squared() + p2.norm_squared(),
        }
    }

    /// The circle's angle (see [`Sp4Lanes::phi_sides`]).
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn phi_sides(&self) -> (f64, f64) {
        self.circle.phi_sides()
    }

    /// How far each distance `d` (given squared) lies outside the distances
    /// `‖rot(k, θ) p1 − p2‖` the circle reaches over θ: positive where `d` is out of
    /// reach, by that much; zero or negative where some θ reaches it.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn miss<const L: usize>(&self, d2: Lanes<L>) -> Lanes<L> {
        // ‖rot p1 − p2‖² = n − 2 p2ᵀ rot p1, and p2ᵀ rot p1 = axial ± √rr at the extremes.
        let c = &self.circle.circle;
        let r = sqrt(c.ca * c.ca + c.sa * c.sa);
        let (near, far) = (self.n - 2.0 * (c.axial + r), self.n - 2.0 * (c.axial - r));
        let (near, far) = (sqrt0(near), sqrt0(far));
        d2.map(|d2| {
            let d = sqrt(d2);
            (d - far).max(near - d)
        })
    }

    /// [`Sp3::solve`] for `L` squared distances `d²` (see [`Sp4Lanes::solve`]).
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn solve<const L: usize>(&self, d2: Lanes<L>) -> Option<RootLanes<L>> {
        let rhs = (Lanes::splat(self.n) - d2) * 0.5;
        self.circle.solve(rhs, (d2 + self.n) * 0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::super::Fit;
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp3_and_its_double_root() {
        let k = V3::z();
        let (p1, p2) = (V3::new(1.0, 0.0, 0.0), V3::new(3.0, 0.0, 0.0));
        let r = sp3(&p1, &p2, &k, 2.5, 0.0);
        assert_eq!(r.n, 2);
        for t in r.thetas() {
            assert!(((rot(&k, t) * p1 - p2).norm() - 2.5).abs() < 1e-14);
        }
        // Tangent: the circle touches the sphere at θ = π (distance 4).
        let r = sp3(&p1, &p2, &k, 4.0, 0.0);
        assert_eq!((r.n, r.fit), (1, Fit::Double));
        assert!((r.angles[0].theta.abs() - core::f64::consts::PI).abs() < 1e-12);
        assert!((r.angles[0].cos + 1.0).abs() < 1e-12);
    }

    #[test]
    fn sp3_lanes_miss_is_the_distance_out_of_reach() {
        // A circle off the sphere's centre and tilted against its axis (p1 not ⟂ k).
        let (k, p1, p2) = (
            unit(0.2, -0.5, 1.0),
            V3::new(0.3, 0.4, -0.2),
            V3::new(-0.1, 0.5, 0.35),
        );
        let elbow = Sp3Lanes::new(&p1, &p2, &k);
        // The distances the circle reaches, swept over θ.
        let (mut near, mut far) = (f64::INFINITY, 0.0_f64);
        for i in 0..100_000 {
            let d = (rot(&k, i as f64 * core::f64::consts::TAU / 1e5) * p1 - p2).norm();
            (near, far) = (near.min(d), far.max(d));
        }
        assert!(near > 0.05 && far - near > 0.1, "{near} {far}");
        let ds = [
            0.5 * near,
            near - 1e-3,
            0.5 * (near + far),
            far + 1e-3,
            2.0 * far,
        ];
        let miss = elbow.miss(Lanes(ds.map(|d| d * d)));
        for (d, miss) in ds.into_iter().zip(miss.0) {
            let want = (d - far).max(near - d);
            // The sweep finds the extremes to (Δθ)² · r ≈ 4e-10.
            assert!((miss - want).abs() < 1e-9, "d {d}: {miss} vs {want}");
            // Out of reach exactly where SP3 has no exact root.
            let fit = sp3(&p1, &p2, &k, d, 0.0).fit;
            assert_eq!(
                miss > 0.0,
                fit == Fit::LeastSquares,
                "d {d}: {miss}, {fit:?}"
            );
        }
    }
}
