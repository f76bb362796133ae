//! **SP1** — `θ` with `rot(k, θ) p1 = p2`: the angle that turns `p1` onto `p2` about `k`.
//! Least squares when the two differ in length or in their component along `k`; free when
//! `p1` or `p2` lies on the axis.
//!
//! Its forms: the angle ([`sp1`]), with its sine and cosine ([`sp1_angle`]), up to its
//! `atan2` ([`sp1_sides`]; two at once, [`sp1_angles_2`]); the same in the plane ⟂ `k`
//! ([`Plane`], [`Planar`], [`sp1_planar`]) for the arms whose middle axes are parallel; and
//! its decision for the lanes of a regular pose ([`sp1_fit_lanes`]).

use super::{Fit, ON_AXIS};
use crate::ik::geometry::{flat, orthogonal, scale, Angle, V3};
use crate::ik::lanes::Lanes;
use crate::math::{fast_atan2 as atan2, fast_atan2_n, sqrt};

/// **SP1** — `θ` with `rot(k, θ) p1 = p2`: the angle that turns `p1` onto `p2` about `k`.
///
/// Least squares (`‖rot(k, θ) p1 − p2‖` minimised) when the two differ in length or in
/// their component along `k`; free (`free` returned) when `p1` or `p2` lies on the axis.
#[inline]
pub fn sp1(p1: &V3, p2: &V3, k: &V3, free: f64) -> (f64, Fit) {
    // Size first: one SP1 in the image, [`sp1_angle`]'s (the same angle, bit for bit).
    if cfg!(feature = "small-ik") {
        let (angle, fit) = sp1_angle(p1, p2, k, free);
        return (angle.theta, fit);
    }
    sp1_from_sides(sp1_sides(p1, p2, k), free)
}

/// SP1's angle from its sides ([`sp1_sides`], [`sp1_planar_sides`]): `atan2(y, x)`, or
/// `free` where the angle is free.
#[inline(always)]
pub fn sp1_from_sides(sides: Option<(f64, f64, Fit)>, free: f64) -> (f64, Fit) {
    match sides {
        Some((y, x, fit)) => (atan2(y, x), fit),
        None => (free, Fit::Free),
    }
}

/// [`sp1`] with the sine and cosine of the angle (from the same products, no `sin`/`cos`
/// call unless the angle is free).
#[cfg_attr(not(feature = "small-ik"), inline)]
#[cfg_attr(feature = "small-ik", inline(never))]
pub fn sp1_angle(p1: &V3, p2: &V3, k: &V3, free: f64) -> (Angle, Fit) {
    match sp1_sides(p1, p2, k) {
        Some((y, x, fit)) => (Angle::atan2(y, x), fit),
        None => (Angle::new(free), Fit::Free),
    }
}

/// SP1 up to its `atan2`: `θ = atan2(y, x)` as `(y, x)` and the fit; `None` when the
/// angle is free. Two of them (independent data) cost one two-lane `atan2` with
/// [`sp1_angles_2`].
#[inline(always)]
pub fn sp1_sides(p1: &V3, p2: &V3, k: &V3) -> Option<(f64, f64, Fit)> {
    let (a, b) = (flat(k, p1), flat(k, p2));
    let lengths = [
        (a.norm_squared(), p1.norm_squared()),
        (b.norm_squared(), p2.norm_squared()),
    ];
    let fit = sp1_fit(lengths, k.dot(p1) - k.dot(p2))?;
    Some((k.dot(&a.cross(&b)), a.dot(&b), fit))
}

/// SP1's decision from what it needs of `p1` and `p2`: per end, the squared length off
/// the axis and the squared length, and the difference of their components along the
/// axis. `None`: an end lies on the axis. The one-lane case of [`sp1_fit_lanes`].
#[inline(always)]
fn sp1_fit(lengths: [(f64, f64); 2], along_gap: f64) -> Option<Fit> {
    let [(na, n1), (nb, n2)] = lengths.map(|(a, n)| (Lanes([a]), Lanes([n])));
    let [exact] = sp1_fit_lanes([(na, n1), (nb, n2)], Lanes([along_gap]))?;
    Some(if exact { Fit::Exact } else { Fit::LeastSquares })
}
/// SP1's decision ([`sp1_fit`]) for `L` lanes at once: `None` when an end lies on the
/// axis in some lane (the angle is free there), else which lanes are exact (the others
/// least squares).
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
pub(crate) fn sp1_fit_lanes<const L: usize>(
    [(na, n1), (nb, n2)]: [(Lanes<L>, Lanes<L>); 2],
    along_gap: Lanes<L>,
) -> Option<[bool; L]> {
    let (s1, s2) = (n1.map(scale), n2.map(scale));
    let room = (s1 + s2) * 1e-18;
    let gap2 = along_gap * along_gap;
    let mut off_axis = true;
    let mut exact = [true; L];
    for (i, exact) in exact.iter_mut().enumerate() {
        // (`!(… <= …)`, not `>`: a NaN length counts as off the axis, and inexact.)
        off_axis &= !((na.0[i] <= ON_AXIS * s1.0[i]) | (nb.0[i] <= ON_AXIS * s2.0[i]));
        // |gap| ≤ 1e-9 √(s1 + s2), squared (no square root).
        *exact =
            ((na.0[i] - nb.0[i]).abs() <= 1e-9 * (na.0[i] + nb.0[i])) & (gap2.0[i] <= room.0[i]);
    }
    off_axis.then_some(exact)
}

/// A vector split for turns about one axis `k`: its coordinates `v` in the plane ⟂ `k`
/// (in an orthonormal basis `(e1, e2)` with `e1 × e2 = k`) and its component `along` `k`.
/// A turn about `k` turns `v` as a 2-D rotation and keeps `along`; SP1 about `k` needs
/// nothing else ([`sp1_planar`]). For the arms whose middle axes are parallel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planar {
    /// In-plane coordinates.
    pub v: [f64; 2],
    /// Component along the axis.
    pub along: f64,
}

impl core::ops::Add for Planar {
    type Output = Planar;

    #[inline]
    fn add(self, other: Planar) -> Planar {
        Planar {
            v: [self.v[0] + other.v[0], self.v[1] + other.v[1]],
            along: self.along + other.along,
        }
    }
}

impl core::ops::Sub for Planar {
    type Output = Planar;

    #[inline]
    fn sub(self, other: Planar) -> Planar {
        Planar {
            v: [self.v[0] - other.v[0], self.v[1] - other.v[1]],
            along: self.along - other.along,
        }
    }
}

impl Planar {
    /// Turned about the axis by the angle whose sine is `sign · a.sin` (`sign` = ±1: an
    /// axis parallel or antiparallel to `k`) and cosine `a.cos`.
    #[inline]
    pub fn turn(self, a: &Angle, sign: f64) -> Planar {
        let (s, c) = (sign * a.sin, a.cos);
        Planar {
            v: [c * self.v[0] - s * self.v[1], s * self.v[0] + c * self.v[1]],
            along: self.along,
        }
    }

    /// The length of the in-plane part.
    #[inline]
    pub fn flat_norm(&self) -> f64 {
        sqrt(self.v[0] * self.v[0] + self.v[1] * self.v[1])
    }
}

/// The plane ⟂ a unit axis `k`, for [`Planar`] coordinates.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    e1: V3,
    e2: V3,
    k: V3,
}

impl Plane {
    /// The plane ⟂ the unit `k`.
    pub fn new(k: &V3) -> Plane {
        let e1 = orthogonal(k).normalize();
        Plane {
            e1,
            e2: k.cross(&e1),
            k: *k,
        }
    }

    /// `v` in this plane's coordinates (out of line with `small-ik`: one copy of its
    /// three dot products for every caller).
    #[cfg_attr(feature = "small-ik", inline(never))]
    #[cfg_attr(not(feature = "small-ik"), inline)]
    pub fn split(&self, v: &V3) -> Planar {
        Planar {
            v: [self.e1.dot(v), self.e2.dot(v)],
            along: self.k.dot(v),
        }
    }

    /// The basis `(e1, e2, k)`: the vectors whose coordinates are `(1, 0, 0)`, `(0, 1, 0)`,
    /// `(0, 0, 1)`.
    #[inline]
    pub fn basis(&self) -> [V3; 3] {
        [self.e1, self.e2, self.k]
    }

    /// The vector whose coordinates are `x`.
    #[inline]
    pub fn join(&self, x: &Planar) -> V3 {
        self.e1 * x.v[0] + self.e2 * x.v[1] + self.k * x.along
    }
}

/// [`sp1`] about the axis of the [`Plane`] `p1` and `p2` are split for: the same
/// decision (exact, least squares, free) from the split vectors, with a 2-D cross product.
#[inline]
pub fn sp1_planar(p1: &Planar, p2: &Planar, free: f64) -> (f64, Fit) {
    sp1_from_sides(sp1_planar_sides(p1, p2), free)
}

/// [`sp1_planar`] up to its `atan2` (as [`sp1_sides`]).
#[inline(always)]
pub fn sp1_planar_sides(p1: &Planar, p2: &Planar) -> Option<(f64, f64, Fit)> {
    let ([a0, a1], [b0, b1]) = (p1.v, p2.v);
    let (na, nb) = (a0 * a0 + a1 * a1, b0 * b0 + b1 * b1);
    let lengths = [
        (na, na + p1.along * p1.along),
        (nb, nb + p2.along * p2.along),
    ];
    let fit = sp1_fit(lengths, p1.along - p2.along)?;
    Some((a0 * b1 - a1 * b0, a0 * b0 + a1 * b1, fit))
}

/// [`sp1_planar`] with the sine and cosine of the angle (as [`sp1_angle`]).
#[inline]
pub fn sp1_planar_angle(p1: &Planar, p2: &Planar, free: f64) -> (Angle, Fit) {
    match sp1_planar_sides(p1, p2) {
        Some((y, x, fit)) => (Angle::atan2(y, x), fit),
        None => (Angle::new(free), Fit::Free),
    }
}

/// The angles of two SP1s from their sides ([`sp1_sides`], [`sp1_planar_sides`]): one
/// two-lane `atan2` when both are determined, `free[i]` where one is free.
#[inline(always)]
pub fn sp1_angles_2(sides: [Option<(f64, f64, Fit)>; 2], free: [f64; 2]) -> [(f64, Fit); 2] {
    match sides {
        [Some((y0, x0, f0)), Some((y1, x1, f1))] => {
            let [t0, t1] = fast_atan2_n([y0, y1], [x0, x1]);
            [(t0, f0), (t1, f1)]
        }
        [a, b] => [sp1_from_sides(a, free[0]), sp1_from_sides(b, free[1])],
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::super::wrap;
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp1_turns_a_point_onto_another() {
        let k = unit(0.2, -0.5, 1.0);
        let p1 = V3::new(0.3, 0.4, -0.2);
        let p2 = rot(&k, 1.1) * p1;
        let (t, fit) = sp1(&p1, &p2, &k, 0.0);
        assert_eq!(fit, Fit::Exact);
        assert!((t - 1.1).abs() < 1e-14);
        assert_eq!(sp1(&(k * 2.0), &p2, &k, 0.25), (0.25, Fit::Free));
        let (_, fit) = sp1(&p1, &(p2 * 2.0), &k, 0.0);
        assert_eq!(fit, Fit::LeastSquares);
    }

    #[test]
    fn sp1_in_the_plane_decides_as_sp1() {
        let k = unit(0.2, -0.5, 1.0);
        let plane = Plane::new(&k);
        let p1 = V3::new(0.3, 0.4, -0.2);
        let turned = rot(&k, 1.1) * p1;
        let cases = [
            (p1, turned),                     // exact
            (p1, turned * 2.0),               // least squares: other length
            (p1, turned + k * 0.1),           // least squares: other height
            (k * 2.0, turned),                // free: p1 on the axis
            (p1, k * -0.5),                   // free: p2 on the axis
            (p1 + k * 0.3, turned + k * 0.3), // exact, off the origin's plane
        ];
        for (a, b) in cases {
            let (want, want_fit) = sp1(&a, &b, &k, 0.25);
            let (got, got_fit) = sp1_planar(&plane.split(&a), &plane.split(&b), 0.25);
            assert_eq!(got_fit, want_fit, "{a:?} {b:?}");
            assert!(wrap(got - want).abs() < 1e-14, "{got} vs {want}");
            // Two at once (3-D and planar sides): the same angles, fits and free values.
            let sides = [
                sp1_sides(&a, &b, &k),
                sp1_planar_sides(&plane.split(&a), &plane.split(&b)),
            ];
            let pair = sp1_angles_2(sides, [0.25, 0.5]);
            let want_free = [0.25, 0.5];
            for (i, &(theta, fit)) in pair.iter().enumerate() {
                assert_eq!(fit, want_fit);
                let want_theta = if fit == Fit::Free { want_free[i] } else { want };
                assert!(
                    wrap(theta - want_theta).abs() < 1e-14,
                    "{theta} vs {want_theta}"
                );
            }
            let (angle, fit) = sp1_planar_angle(&plane.split(&a), &plane.split(&b), 0.25);
            assert_eq!((angle.theta, fit), (got, got_fit));
            assert!((angle.sin - got.sin()).abs() < 1e-15 && (angle.cos - got.cos()).abs() < 1e-15);
        }
    }

    #[test]
    fn planar_turns_are_rotations_about_the_axis() {
        let k = unit(-0.7, 0.1, 0.4);
        let plane = Plane::new(&k);
        let p = V3::new(0.5, -0.3, 0.8);
        for (theta, sign) in [(0.4, 1.0), (-2.2, 1.0), (1.3, -1.0)] {
            let a = Angle::new(theta);
            let want = rot(&k, sign * theta) * p;
            let got = plane.join(&plane.split(&p).turn(&a, sign));
            assert!((got - want).norm() < 1e-15, "{got:?} {want:?}");
        }
        let (u, v) = (V3::new(1.0, 2.0, 3.0), V3::new(-0.5, 0.25, 4.0));
        let (su, sv) = (plane.split(&u), plane.split(&v));
        assert!((plane.join(&(su + sv)) - (u + v)).norm() < 1e-14);
        assert!((plane.join(&(su - sv)) - (u - v)).norm() < 1e-14);
        assert!((su.flat_norm() - (u - k * k.dot(&u)).norm()).abs() < 1e-14);
    }
}
