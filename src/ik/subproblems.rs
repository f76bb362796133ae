//! The geometric subproblems closed-form IK is built from (Paden–Kahan 1–3, Elias–Wen 4),
//! each with its geometric statement, least-squares behaviour and degenerate cases.
//!
//! Every axis `k` is a unit vector. Angles come back as radians; a result says whether it
//! is exact, least squares (the data admit no exact solution, so the nearest is given),
//! or free (the data leave the angle undetermined — a singular configuration — and the
//! caller's `free` value is used). A discriminant within [`ROOT_MERGE`] rounding errors of
//! zero — the error estimated from the size of the terms it was computed from — is a
//! double root: that is what an exactly singular pose computed in floating point looks
//! like, and splitting it into two roots `±1e-8` apart would make the angles after it
//! meaningless.

use super::geometry::{flat, orthogonal, scale, sqrt0, Angle, V3};
use super::lanes::Lanes;
use crate::math::{fast_atan2 as atan2, fast_atan2_n, sqrt};

/// A discriminant smaller than this many times its estimated rounding error
/// (`ε · terms`) is zero: the two roots are one double root.
pub const ROOT_MERGE: f64 = 64.0;

/// Machine epsilon.
const EPS: f64 = f64::EPSILON;

/// A discriminant below this fraction of `r²` is also a double root: roots closer than
/// `2√1e-11 ≈ 6e-6` rad. Errors upstream (the angles a subproblem's data came from)
/// blur a double root more than its own terms' rounding; taking the two roots as one
/// moves the solution by at most ~3e-6 rad along a direction where the equation is
/// flat to second order (≤ 1e-11 relative), and the branch is checked against `fk`
/// afterwards anyway (its fit is `Double`).
const MERGE_RELATIVE: f64 = 1e-11;

/// Relative size (squared) of a vector's component off an axis below which the vector is
/// taken to lie on the axis: the rotation about that axis leaves it where it is.
pub const ON_AXIS: f64 = 1e-18;

/// How a subproblem's solution relates to the data, from the strongest to the weakest
/// (the order [`Fit::and`] uses).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Fit {
    /// Solves the equations (to rounding).
    Exact,
    /// A double root (two solutions that met): exact, at a singular configuration.
    Double,
    /// The angle is free (any value solves it): the caller's value was used.
    Free,
    /// The nearest solution: the equations have none.
    LeastSquares,
}

impl Fit {
    /// The weaker of two fits (least squares dominates, then free, then double).
    #[inline]
    pub fn and(self, other: Fit) -> Fit {
        self.max(other)
    }
}

/// Up to two angles, with their sines and cosines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roots {
    /// The angles; `angles[..n]` are used.
    pub angles: [Angle; 2],
    /// How many (1 or 2).
    pub n: usize,
    /// How they fit.
    pub fit: Fit,
}

impl Roots {
    #[inline]
    fn one(angle: Angle, fit: Fit) -> Roots {
        Roots {
            angles: [angle, angle],
            n: 1,
            fit,
        }
    }

    /// The angles.
    #[inline]
    pub fn as_slice(&self) -> &[Angle] {
        &self.angles[..self.n]
    }

    /// The angles' values.
    #[inline]
    pub fn thetas(&self) -> impl Iterator<Item = f64> + '_ {
        self.as_slice().iter().map(|a| a.theta)
    }
}

/// **SP1** — `θ` with `rot(k, θ) p1 = p2`: the angle that turns `p1` onto `p2` about `k`.
///
/// Least squares (`‖rot(k, θ) p1 − p2‖` minimised) when the two differ in length or in
/// their component along `k`; free (`free` returned) when `p1` or `p2` lies on the axis.
#[inline]
pub fn sp1(p1: &V3, p2: &V3, k: &V3, free: f64) -> (f64, Fit) {
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
#[inline]
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

    /// `v` in this plane's coordinates.
    #[inline]
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

/// `θ = φ ± atan2(√(r² − b²), b)` for `a cos θ + a' sin θ = b` written as
/// `r cos(θ − φ) = b`: two roots, a double root, or the least-squares `φ` / `φ + π`.
/// `mag2` is the squared size of the data (`‖h‖²‖p‖²`): `r` is zero relative to it;
/// `terms` the size of the terms `b` was computed from (its rounding error is `ε terms`).
///
/// With `cos φ = a / r`, `sin φ = a' / r`, `cos d = b / r`, `sin d = √(r² − b²) / r`, the
/// roots `φ ± d` have `cos = (a b ∓ a' √…) / r²` and `sin = (a' b ± a √…) / r²`: one
/// `atan2` per root and no `sin`/`cos` for the rotations built from it.
///
/// With `phi` (the angle of `(ca, sa)`, known when the same circle is cut many times) each
/// pair of roots costs one `atan2`, for `d`: `θ = φ ± d`.
fn cos_equation(
    ca: f64,
    sa: f64,
    b: f64,
    terms: f64,
    mag2: f64,
    free: f64,
    phi: Option<Angle>,
) -> Roots {
    let rr = ca * ca + sa * sa;
    let sd = match cos_case(rr, b, terms, mag2) {
        CosCase::Two { sd } => sd,
        CosCase::NoCircle { fit } => return Roots::one(Angle::new(free), fit),
        CosCase::One { fit } => {
            // θ = φ where b ≥ 0, else φ + π: the nearest to r cos(θ − φ) = b.
            let sign = if b >= 0.0 { 1.0 } else { -1.0 };
            let angle = match phi {
                Some(phi) if sign > 0.0 => phi,
                Some(phi) => half_turn(phi),
                None => Angle::atan2(sign * sa, sign * ca),
            };
            return Roots::one(angle, fit);
        }
    };
    // φ ± d, with d = atan2(√(r² − b²), b) ∈ [0, π].
    let thetas = match phi {
        Some(phi) => roots_of(phi.theta, atan2(sd, b)),
        None => fast_atan2_n(
            [sa * b + ca * sd, sa * b - ca * sd],
            [ca * b - sa * sd, ca * b + sa * sd],
        ),
    };
    two_roots(ca, sa, b, sd, rr, thetas)
}

/// Which solutions `a cos θ + a' sin θ = b` has (see [`cos_equation`]).
#[derive(Clone, Copy)]
enum CosCase {
    /// `r = 0`: every θ gives the same value (free if it is `b`, else least squares).
    NoCircle { fit: Fit },
    /// One root: a double root, or the least-squares `φ` / `φ + π`.
    One { fit: Fit },
    /// Two roots `φ ± d`, with `sin d = sd / r`.
    Two { sd: f64 },
}

/// [`cos_equation`]'s decision, from `rr = r²`, `b` and the sizes its rounding errors are
/// estimated from.
#[inline(always)]
fn cos_case(rr: f64, b: f64, terms: f64, mag2: f64) -> CosCase {
    if rr <= ON_AXIS * scale(mag2) {
        // r = 0: every θ gives the same value; exact only if that is b.
        let fit = if b * b <= 1e-18 * scale(mag2) {
            Fit::Free
        } else {
            Fit::LeastSquares
        };
        return CosCase::NoCircle { fit };
    }
    let disc = rr - b * b;
    // `2√rr (terms + √mag2) ≤ rr + 2 terms² + 2 mag2` (AM–GM twice): a discriminant above
    // that bound's merge distance is no double root, whatever the noise; only those
    // within it pay for the noise's two square roots.
    let bound = EPS * (2.0 * rr + 2.0 * (terms * terms + mag2));
    let double = disc.abs() <= (ROOT_MERGE * bound).max(MERGE_RELATIVE * rr) && {
        let noise = EPS * (2.0 * sqrt(rr) * (terms + sqrt(mag2)) + rr);
        disc.abs() <= (ROOT_MERGE * noise).max(MERGE_RELATIVE * rr)
    };
    if double {
        CosCase::One { fit: Fit::Double }
    } else if disc < 0.0 {
        CosCase::One {
            fit: Fit::LeastSquares,
        }
    } else {
        CosCase::Two { sd: sqrt0(disc) }
    }
}

/// The two roots `φ ± d` of `r cos(θ − φ) = b` (angles `thetas`), with their sines and
/// cosines from the same products: `cos = (a b ∓ a' √…) / r²`, `sin = (a' b ± a √…) / r²`.
#[inline(always)]
fn two_roots(ca: f64, sa: f64, b: f64, sd: f64, rr: f64, thetas: [f64; 2]) -> Roots {
    let inv = 1.0 / rr;
    Roots {
        angles: [
            Angle {
                theta: thetas[0],
                sin: (sa * b + ca * sd) * inv,
                cos: (ca * b - sa * sd) * inv,
            },
            Angle {
                theta: thetas[1],
                sin: (sa * b - ca * sd) * inv,
                cos: (ca * b + sa * sd) * inv,
            },
        ],
        n: 2,
        fit: Fit::Exact,
    }
}

/// **SP4** — `θ` with `hᵀ rot(k, θ) p = d`: where the circle of `p` about `k` crosses the
/// plane `hᵀ x = d`. Two roots, a double root (the circle touches the plane), least
/// squares (it misses the plane), or free (the circle lies in a plane `hᵀ x = d`).
pub fn sp4(h: &V3, p: &V3, k: &V3, d: f64, free: f64) -> Roots {
    sp4_terms(h, p, k, d, d.abs(), free)
}

/// SP4 where `d` was computed from terms of size `terms` (its rounding error).
fn sp4_terms(h: &V3, p: &V3, k: &V3, d: f64, terms: f64, free: f64) -> Roots {
    let c = Sp4Circle::terms(h, p, k);
    cos_equation(c.ca, c.sa, d - c.axial, terms, c.mag2, free, None)
}

/// What SP4 needs of `h`, `p`, `k` (`hᵀ rot(k, θ) p = ca cos θ + sa sin θ + axial`).
#[derive(Clone, Copy, Debug)]
struct Sp4Circle {
    ca: f64,
    sa: f64,
    axial: f64,
    mag2: f64,
}

impl Sp4Circle {
    #[inline(always)]
    fn terms(h: &V3, p: &V3, k: &V3) -> Sp4Circle {
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

    #[inline]
    fn solve_terms(&self, d: f64, terms: f64, free: f64) -> Roots {
        let c = &self.circle;
        cos_equation(c.ca, c.sa, d - c.axial, terms, c.mag2, free, self.phi)
    }
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

/// The roots of one circle cut in each of `L` lanes, for a regular pose: a lane has two
/// distinct exact roots `φ ± d`, or (`exact[i]` false) misses the circle and has the
/// least-squares root `φ` or `φ + π` (as `d = 0` or `π`, both roots the same). Their
/// sines and cosines are here (as [`Roots`] has them); their angles wait for one batch of
/// `atan2` with the rest of the solve: `d = atan2(y, x)`, `θ = wrap(φ ± d)` with the
/// circle's `φ` ([`Sp4Lanes::phi_sides`]).
#[derive(Clone, Copy, Debug)]
pub struct RootLanes<const L: usize> {
    /// `sin` of `φ + d` and of `φ − d`.
    pub sin: [Lanes<L>; 2],
    /// `cos` of `φ + d` and of `φ − d`.
    pub cos: [Lanes<L>; 2],
    /// `d = atan2(y, x)`.
    pub y: Lanes<L>,
    /// See `y`.
    pub x: Lanes<L>,
    /// Lanes with two exact roots (the others one least-squares root).
    pub exact: [bool; L],
}

/// The two roots `φ ± d` of a lane, wrapped.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
pub fn roots_of(phi: f64, d: f64) -> [f64; 2] {
    [wrap(phi + d), wrap(phi - d)]
}

/// [`Sp4`] for the branches of a level side by side: one circle `hᵀ rot(k, θ) p`, cut
/// by `L` planes at once. Its angle `φ` is left to the caller's batch of `atan2`.
#[derive(Clone, Copy, Debug)]
pub struct Sp4Lanes {
    circle: Sp4Circle,
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

/// `θ + π`, wrapped into `(−π, π]`, with its sine and cosine (those of `θ`, negated).
#[inline]
pub fn half_turn(a: Angle) -> Angle {
    Angle {
        theta: wrap(a.theta + core::f64::consts::PI),
        sin: -a.sin,
        cos: -a.cos,
    }
}

/// `θ` wrapped into `(−π, π]`.
#[inline]
pub fn wrap(theta: f64) -> f64 {
    use core::f64::consts::{PI, TAU};
    // Solver angles come from atan2 and sums of a few of them: almost always within one
    // turn, where a comparison is enough (`%` is a libm call, a fifth of a solve).
    let inside = |t: f64| t > -PI && t <= PI;
    if inside(theta) {
        return theta;
    }
    let t = if theta > PI { theta - TAU } else { theta + TAU };
    if inside(t) {
        return t;
    }
    // Further out (a caller's free value), or NaN: reduce exactly.
    let t = theta % TAU;
    if t > PI {
        t - TAU
    } else if t <= -PI {
        t + TAU
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::super::geometry::rot;
    use super::*;

    fn unit(x: f64, y: f64, z: f64) -> V3 {
        V3::new(x, y, z).normalize()
    }

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

    #[test]
    fn wrap_is_into_the_half_open_turn() {
        use core::f64::consts::PI;
        assert_eq!(wrap(PI), PI);
        assert!((wrap(-PI) - PI).abs() < 1e-15);
        assert!((wrap(7.0) - (7.0 - 2.0 * PI)).abs() < 1e-15);
    }
}
