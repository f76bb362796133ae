//! The geometric subproblems closed-form IK is built from (Paden–Kahan 1–3, Elias–Wen 4–6),
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
//!
//! One file per subproblem, its scalar and lane forms together: SP1 ([`sp1()`], in the
//! plane ⟂ its axis [`sp1_planar`]), SP2 ([`sp2()`]), SP3 ([`sp3()`], [`Sp3`],
//! [`Sp3Lanes`]), SP4 ([`sp4()`], [`Sp4`], [`Sp4Lanes`]), SP5 ([`sp5()`]) and SP6
//! ([`sp6()`], [`two_sinusoids`]) with the quartic both come down to ([`TrigQuadratic`],
//! `quartic.rs`), and for a prismatic joint the slide to a distance ([`slide()`],
//! `slide.rs`). Here, what they share: the fits
//! ([`Fit`]) and roots ([`Roots`], [`RootLanes`]) they return, the tolerances, the
//! equation `a cos θ + a' sin θ = b` that SP3 and SP4 come down to, and angle wrapping
//! ([`wrap`], [`half_turn`]).

use super::geometry::{scale, sqrt0, Angle};
use super::lanes::Lanes;
use crate::math::{fast_atan2 as atan2, fast_atan2_n, sqrt};

mod quartic;
mod slide;
mod sp1;
mod sp2;
mod sp3;
mod sp4;
mod sp5;
mod sp6;

pub use quartic::{QuarticRoots, TrigQuadratic, NEAR_PAIR};
pub use slide::slide;
pub(crate) use sp1::sp1_fit_lanes;
pub use sp1::{
    sp1, sp1_angle, sp1_angles_2, sp1_from_sides, sp1_planar, sp1_planar_angle, sp1_planar_sides,
    sp1_sides, Planar, Plane,
};
pub use sp2::{sp2, Sp2Lanes};
pub use sp3::{sp3, Sp3, Sp3Lanes};
pub use sp4::{sp4, Sp4, Sp4Lanes};
pub use sp5::{sp5, Sp5Roots};
pub use sp6::{sp6, two_sinusoids, Sp6Roots};

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
pub(super) const MERGE_RELATIVE: f64 = 1e-11;

/// How far apart two roots that a subproblem takes as one double root may be (a
/// discriminant below `1e-11 r²`): `2√1e-11` rad; a merged root lies within half of it
/// of each.
pub const MERGE_DISTANCE: f64 = 6.324_555_320_336_758e-6;

/// Relative size (squared) of a vector's component off an axis below which the vector is
/// taken to lie on the axis: the rotation about that axis leaves it where it is.
pub const ON_AXIS: f64 = 1e-18;

/// How a subproblem's solution relates to the data, from the strongest to the weakest
/// (the order [`Fit::and`] uses).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Fit {
    /// Solves the equations (to rounding).
    Exact,
    /// Solves the equations to a root finder's accuracy (a root of SP5's or SP6's
    /// quartic): checked against `fk` before it is called exact.
    Checked,
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

/// Up to four solutions of a subproblem whose first step is a quartic — the roots of a
/// trigonometric quadratic ([`QuarticRoots`]), SP6's pairs ([`Sp6Roots`]), SP5's triples
/// ([`Sp5Roots`]) — each with how it fits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourRoots<T> {
    items: [T; 4],
    fits: [Fit; 4],
    n: usize,
}

impl<T: Copy> FourRoots<T> {
    /// None yet (`fill` only pads the unused slots).
    pub(super) fn empty(fill: T) -> Self {
        FourRoots {
            items: [fill; 4],
            fits: [Fit::Exact; 4],
            n: 0,
        }
    }

    /// One more (at most four: the quartic's degree).
    pub(super) fn push(&mut self, x: T, fit: Fit) {
        self.items[self.n] = x;
        self.fits[self.n] = fit;
        self.n += 1;
    }

    /// The solutions, without their fits.
    pub fn as_slice(&self) -> &[T] {
        &self.items[..self.n]
    }

    /// How many.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The solutions and their fits.
    pub fn iter(&self) -> impl Iterator<Item = (T, Fit)> + '_ {
        self.as_slice()
            .iter()
            .copied()
            .zip(self.fits[..self.n].iter().copied())
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
        // `n` is 1 or 2; `get` keeps a panic path out of every `ik`.
        self.angles.get(..self.n).unwrap_or(&[])
    }

    /// The angles' values.
    #[inline]
    pub fn thetas(&self) -> impl Iterator<Item = f64> + '_ {
        self.as_slice().iter().map(|a| a.theta)
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
    // Further out (a caller's free value), or NaN: reduce exactly (`%` by TAU, without
    // linking the general `fmod`).
    let t = crate::math::rem_tau(theta);
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
    use super::*;
    use crate::ik::geometry::V3;

    /// The unit vector along `(x, y, z)` (for the subproblems' tests).
    pub(super) fn unit(x: f64, y: f64, z: f64) -> V3 {
        V3::new(x, y, z).normalize()
    }

    #[test]
    fn merge_distance_is_twice_the_root_of_merge_relative() {
        assert_eq!(MERGE_DISTANCE, 2.0 * MERGE_RELATIVE.sqrt());
    }

    #[test]
    fn wrap_is_into_the_half_open_turn() {
        use core::f64::consts::PI;
        assert_eq!(wrap(PI), PI);
        assert!((wrap(-PI) - PI).abs() < 1e-15);
        assert!((wrap(7.0) - (7.0 - 2.0 * PI)).abs() < 1e-15);
    }
}
