//! The equation SP5 and SP6 come down to — a **trigonometric quadratic** in one angle,
//!
//! `Q(θ) = c0 + c1 cos θ + s1 sin θ + c2 cos 2θ + s2 sin 2θ = 0`,
//!
//! (a conic cut by the unit circle) — and its up to four roots. With `t = tan((θ − θ0)/2)`
//! it is a quartic in `t`, `(1 + t²)² Q = e4 t⁴ + e3 t³ + e2 t² + e1 t + e0`, whose leading
//! coefficient is `Q(θ0 + π)`: `θ0 + π` is taken where `|Q|` is largest of eight samples
//! `kπ/4` (a nonzero `Q` has at most four roots, so never all eight vanish), so that no root
//! runs off to `t = ∞` and the quartic is well scaled. Ferrari's resolvent cubic factors it
//! into two quadratics; each real root is then polished by Newton steps on the quartic.
//!
//! A pair of complex roots whose imaginary part is within [`NEAR_PAIR`], or two real roots
//! that close, is a double root (the conic touches the circle: a singular configuration)
//! blurred by rounding, and its real part (their midpoint) is one root flagged
//! [`Fit::Double`]. Where `Q` has no real root at all, the
//! real part of the pair nearest the real axis is given, flagged [`Fit::LeastSquares`].
//! The callers check every branch built on these roots against the robot's `fk`.

use super::{Fit, FourRoots};
use crate::ik::geometry::Angle;
use crate::math::{acos, fast_atan2 as atan2, sin_cos, sqrt};
use core::f64::consts::FRAC_1_SQRT_2;

/// A complex pair `re ± i·im` with `|im| ≤ NEAR_PAIR (1 + |re|)` (in `t`), or two real
/// roots that close, is a double root. A double root perturbed by `δ` (relative) splits by `~√δ`: rounding (`δ ~ 1e-16`)
/// moves it by ~1e-8, upstream error in the coefficients (1e-13 relative) by ~3e-7.
pub const NEAR_PAIR: f64 = 1e-5;

/// `Q(θ) = c0 + c1 cos θ + s1 sin θ + c2 cos 2θ + s2 sin 2θ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrigQuadratic {
    /// Constant term.
    pub c0: f64,
    /// Coefficient of `cos θ`.
    pub c1: f64,
    /// Coefficient of `sin θ`.
    pub s1: f64,
    /// Coefficient of `cos 2θ`.
    pub c2: f64,
    /// Coefficient of `sin 2θ`.
    pub s2: f64,
}

/// Up to four roots of a [`TrigQuadratic`], with their sines and cosines; each fits as
/// [`Fit::Exact`] (a simple real root), [`Fit::Double`] (a complex pair within rounding of
/// the real axis) or [`Fit::LeastSquares`] (no real root: the pair nearest to one). None
/// only for `Q ≡ 0` or non-finite coefficients.
pub type QuarticRoots = FourRoots<Angle>;

impl TrigQuadratic {
    /// `Q(θ)` from `cos θ`, `sin θ`.
    #[inline]
    pub fn at(&self, c: f64, s: f64) -> f64 {
        self.c0 + self.c1 * c + self.s1 * s + self.c2 * (c * c - s * s) + self.s2 * (2.0 * s * c)
    }

    /// The coefficients of `Q(θ + a)` as a function of `θ`, for `cos a = c`, `sin a = s`.
    fn shifted(&self, c: f64, s: f64) -> TrigQuadratic {
        let (c2a, s2a) = (c * c - s * s, 2.0 * s * c);
        TrigQuadratic {
            c0: self.c0,
            c1: self.c1 * c + self.s1 * s,
            s1: self.s1 * c - self.c1 * s,
            c2: self.c2 * c2a + self.s2 * s2a,
            s2: self.s2 * c2a - self.c2 * s2a,
        }
    }

    /// The real roots (see the module).
    pub fn roots(&self) -> QuarticRoots {
        let mut out = QuarticRoots::empty(Angle::new(0.0));
        // The sample where |Q| is largest goes to t = ∞ (θ0 = sample − π).
        const UNIT: [(f64, f64); 8] = [
            (1.0, 0.0),
            (FRAC_1_SQRT_2, FRAC_1_SQRT_2),
            (0.0, 1.0),
            (-FRAC_1_SQRT_2, FRAC_1_SQRT_2),
            (-1.0, 0.0),
            (-FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
            (0.0, -1.0),
            (FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
        ];
        let (mut best, mut k) = (-1.0, 0);
        for (i, &(c, s)) in UNIT.iter().enumerate() {
            let v = self.at(c, s).abs();
            if v > best {
                (best, k) = (v, i);
            }
        }
        if best <= 0.0 || !best.is_finite() {
            return out;
        }
        // θ0 = kπ/4 − π: cos θ0 = −cos(kπ/4), sin θ0 = −sin(kπ/4).
        let (c0, s0) = (-UNIT[k].0, -UNIT[k].1);
        let q = self.shifted(c0, s0);
        let e4 = q.c0 - q.c1 + q.c2;
        let e3 = 2.0 * q.s1 - 4.0 * q.s2;
        let e2 = 2.0 * q.c0 - 6.0 * q.c2;
        let e1 = 2.0 * q.s1 + 4.0 * q.s2;
        let e0 = q.c0 + q.c1 + q.c2;
        let coefficients = [e3 / e4, e2 / e4, e1 / e4, e0 / e4];
        let roots = quartic(coefficients);
        let to_angle = |t: f64| {
            // cos, sin of φ = 2 atan t, then turned by θ0.
            let d = 1.0 / (1.0 + t * t);
            let (cp, sp) = ((1.0 - t * t) * d, 2.0 * t * d);
            let (c, s) = (cp * c0 - sp * s0, sp * c0 + cp * s0);
            Angle {
                theta: atan2(s, c),
                sin: s,
                cos: c,
            }
        };
        // The real roots (with the real parts of near pairs), in order, then merged.
        let mut real = [(0.0, Fit::Exact); 4];
        let mut n = 0;
        let mut nearest: Option<(f64, f64)> = None;
        for &(re, im) in &roots {
            if im == 0.0 {
                real[n] = (re, conditioned(re, coefficients));
                n += 1;
            } else if im > 0.0 {
                // One of each pair (the other is its conjugate).
                let off = im / (1.0 + re.abs());
                if off <= NEAR_PAIR {
                    real[n] = (re, Fit::Double);
                    n += 1;
                } else if nearest.is_none_or(|(_, o)| off < o) {
                    nearest = Some((re, off));
                }
            }
        }
        let real = &mut real[..n];
        real.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let mut i = 0;
        while i < real.len() {
            let (mut t, mut fit) = real[i];
            // Two real roots within NEAR_PAIR are one double root split by rounding, as is a
            // near pair. Each of them is only good to ~√ε; the double root is a simple
            // root of the derivative, found there to rounding.
            if i + 1 < real.len() && real[i + 1].0 - t <= NEAR_PAIR * (1.0 + t.abs()) {
                (t, fit) = (0.5 * (t + real[i + 1].0), Fit::Double);
                i += 1;
            }
            if fit == Fit::Double {
                t = critical_point(t, coefficients);
            }
            out.push(to_angle(t), fit);
            i += 1;
        }
        if out.is_empty() {
            if let Some((re, _)) = nearest {
                out.push(to_angle(re), Fit::LeastSquares);
            }
        }
        out
    }
}

/// The four roots `(re, im)` of the monic quartic `t⁴ + a t³ + b t² + c t + d` (each complex
/// pair once with `im > 0` and once with `im < 0`; real roots with `im = 0`, polished by
/// Newton steps), by Ferrari's method.
pub fn quartic([a, b, c, d]: [f64; 4]) -> [(f64, f64); 4] {
    // t = y − a/4: y⁴ + p y² + q y + r.
    let a4 = a * 0.25;
    let aa = a * a;
    let p = b - 0.375 * aa;
    let q = c - 0.5 * a * b + 0.125 * aa * a;
    let r = d - a4 * c + aa * b / 16.0 - 3.0 * aa * aa / 256.0;
    let mut y = [(0.0, 0.0); 4];
    // The resolvent's largest root m ≥ 0: y⁴ + p y² + q y + r =
    // (y² + p/2 + m)² − 2m (y − q/(4m))².
    let m = cubic_largest(p, 0.25 * p * p - r, -0.125 * q * q);
    if m > 0.0 && q != 0.0 {
        let s2m = sqrt(2.0 * m);
        for (k, s) in [1.0, -1.0].into_iter().enumerate() {
            // y² + s√(2m) y + (p/2 + m − s q / (2√(2m))) = 0
            let disc = -2.0 * p - 2.0 * m + s * 2.0 * q / s2m;
            let centre = -0.5 * s * s2m;
            y[2 * k..2 * k + 2].copy_from_slice(&quadratic_pair(centre, disc));
        }
    } else {
        // Biquadratic: z = y², z² + p z + r = 0.
        let disc = p * p - 4.0 * r;
        let zs = if disc >= 0.0 {
            let sq = sqrt(disc);
            let z1 = -0.5 * (p + if p >= 0.0 { sq } else { -sq });
            let z2 = if z1 != 0.0 { r / z1 } else { 0.0 };
            [(z1, 0.0), (z2, 0.0)]
        } else {
            let im = 0.5 * sqrt(-disc);
            [(-0.5 * p, im), (-0.5 * p, -im)]
        };
        for (k, z) in zs.into_iter().enumerate() {
            let (re, im) = csqrt(z);
            y[2 * k] = (re, im);
            y[2 * k + 1] = (-re, -im);
        }
    }
    y.map(|(re, im)| {
        let t = re - a4;
        if im != 0.0 {
            return (t, im);
        }
        (newton(t, [a, b, c, d]), 0.0)
    })
}

/// The two roots of `y² − 2 centre y + …` given as `centre ± √disc / 2`, complex where
/// `disc < 0`.
fn quadratic_pair(centre: f64, disc: f64) -> [(f64, f64); 2] {
    if disc >= 0.0 {
        let h = 0.5 * sqrt(disc);
        [(centre + h, 0.0), (centre - h, 0.0)]
    } else {
        let h = 0.5 * sqrt(-disc);
        [(centre, h), (centre, -h)]
    }
}

/// `√z` for complex `z = (re, im)`, on the principal branch.
fn csqrt((re, im): (f64, f64)) -> (f64, f64) {
    if im == 0.0 {
        return if re >= 0.0 {
            (sqrt(re), 0.0)
        } else {
            (0.0, sqrt(-re))
        };
    }
    let r = sqrt(re * re + im * im);
    let x = sqrt(0.5 * (r + re));
    let y = sqrt(0.5 * (r - re));
    (x, if im >= 0.0 { y } else { -y })
}

/// The largest real root of `m³ + p m² + u m + v` (with `v ≤ 0` it is `≥ 0`), polished by
/// Newton steps.
fn cubic_largest(p: f64, u: f64, v: f64) -> f64 {
    // m = z − p/3: z³ + P z + R.
    let p3 = p / 3.0;
    let pp = u - p * p3;
    let rr = 2.0 * p3 * p3 * p3 - p3 * u + v;
    let disc = 0.25 * rr * rr + pp * pp * pp / 27.0;
    let z = if disc > 0.0 {
        let s = sqrt(disc);
        // u = ∛(−R/2 ∓ √disc) with the sign that avoids cancellation.
        let w = if rr >= 0.0 {
            -0.5 * rr - s
        } else {
            -0.5 * rr + s
        };
        let u = cbrt(w);
        if u == 0.0 {
            0.0
        } else {
            u - pp / (3.0 * u)
        }
    } else {
        let rho = sqrt(-pp / 3.0);
        if rho == 0.0 {
            0.0
        } else {
            let arg = (-rr / (2.0 * rho * rho * rho)).clamp(-1.0, 1.0);
            2.0 * rho * sin_cos(acos(arg) / 3.0).1
        }
    };
    let mut m = z - p3;
    for _ in 0..2 {
        let f = ((m + p) * m + u) * m + v;
        let df = (3.0 * m + 2.0 * p) * m + u;
        if df == 0.0 {
            break;
        }
        let next = m - f / df;
        if !next.is_finite() {
            break;
        }
        m = next;
    }
    m.max(0.0)
}

fn cbrt(x: f64) -> f64 {
    libm::cbrt(x)
}

/// How a real root `t` of the monic quartic fits: [`Fit::Exact`] where rounding in the
/// coefficients (taken as [`COEFFICIENT_ERROR`] of the terms' size) moves it by less than
/// [`ROOT_ERROR`], else [`Fit::Double`] — a cluster of roots (three or four meeting at a
/// singular pose), which rounding scatters by `ε^(1/3)` or `ε^(1/4)`, for the family to
/// polish on `fk`.
fn conditioned(t: f64, [a, b, c, d]: [f64; 4]) -> Fit {
    let at = t.abs();
    let size = (((at + a.abs()) * at + b.abs()) * at + c.abs()) * at + d.abs();
    let slope = (((4.0 * t + 3.0 * a) * t + 2.0 * b) * t + c).abs();
    if COEFFICIENT_ERROR * size <= ROOT_ERROR * (1.0 + at) * slope {
        Fit::Exact
    } else {
        Fit::Double
    }
}

/// Relative error assumed in the quartic's coefficients (they come from products of the
/// pose's and the geometry's terms, with cancellation).
const COEFFICIENT_ERROR: f64 = 1e-13;

/// Largest error (in `t`, relative to `1 + |t|`) of a root called [`Fit::Exact`].
const ROOT_ERROR: f64 = 1e-9;

/// The root of the monic quartic's derivative near `t` (a double root of the quartic, which
/// is a simple root of the derivative).
fn critical_point(t: f64, [a, b, c, _]: [f64; 4]) -> f64 {
    descend(
        t,
        |t| ((4.0 * t + 3.0 * a) * t + 2.0 * b) * t + c,
        |t| (12.0 * t + 6.0 * a) * t + 2.0 * b,
    )
}

/// A root of the monic quartic near `t`.
fn newton(t: f64, [a, b, c, d]: [f64; 4]) -> f64 {
    descend(
        t,
        |t| (((t + a) * t + b) * t + c) * t + d,
        |t| ((4.0 * t + 3.0 * a) * t + 2.0 * b) * t + c,
    )
}

/// Up to three Newton steps on `f` from `t`, each kept only where it shrinks `|f|`.
fn descend(mut t: f64, f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64) -> f64 {
    let mut ft = f(t);
    for _ in 0..3 {
        let slope = df(t);
        if slope == 0.0 || ft == 0.0 {
            break;
        }
        let next = t - ft / slope;
        let f_next = f(next);
        if f_next.is_nan() || f_next.abs() >= ft.abs() {
            break;
        }
        (t, ft) = (next, f_next);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::super::wrap;
    use super::*;
    use core::f64::consts::PI;
    use std::vec::Vec;

    /// Q(θ) = Π (cos θ − cos r_i)-like products: a trig quadratic with the roots `r`.
    fn with_roots(r: [f64; 4], scale: f64) -> TrigQuadratic {
        // (cos θ − cos α)(cos θ − cos β)... is not general; build from two factors
        // sin((θ − a)/2) sin((θ − b)/2) ∝ cos(a − b)/2 − cos(θ − (a + b)/2): a trig linear.
        let lin = |a: f64, b: f64| {
            let m = 0.5 * (a + b);
            // L(θ) = cos((a − b)/2) − cos(θ − m) = k − cos m cos θ − sin m sin θ
            ((0.5 * (a - b)).cos(), -m.cos(), -m.sin())
        };
        let (k1, x1, y1) = lin(r[0], r[1]);
        let (k2, x2, y2) = lin(r[2], r[3]);
        // (k1 + x1 c + y1 s)(k2 + x2 c + y2 s)
        // c² = (1 + cos2)/2, s² = (1 − cos2)/2, cs = sin2/2.
        TrigQuadratic {
            c0: scale * (k1 * k2 + 0.5 * (x1 * x2 + y1 * y2)),
            c1: scale * (k1 * x2 + k2 * x1),
            s1: scale * (k1 * y2 + k2 * y1),
            c2: scale * 0.5 * (x1 * x2 - y1 * y2),
            s2: scale * 0.5 * (x1 * y2 + x2 * y1),
        }
    }

    fn sorted(mut v: Vec<f64>) -> Vec<f64> {
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v
    }

    #[test]
    fn four_known_roots_anywhere_on_the_circle() {
        // A fixed pseudo-random sweep: roots anywhere, including ±π and near each other.
        let mut x: u64 = 0x9e3779b97f4a7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * PI - PI
        };
        for case in 0..2000 {
            let r = [next(), next(), next(), next()];
            let q = with_roots(r, 10f64.powi(case % 7 - 3));
            let got = q.roots();
            let min_gap = (0..4)
                .flat_map(|i| (0..4).filter(move |&j| j > i).map(move |j| (i, j)))
                .map(|(i, j)| wrap(r[i] - r[j]).abs())
                .fold(f64::INFINITY, f64::min);
            if min_gap < 1e-3 {
                continue;
            }
            assert_eq!(got.len(), 4, "{r:?} {got:?}");
            let want = sorted(r.iter().map(|&t| wrap(t)).collect());
            let have = sorted(got.as_slice().iter().map(|a| a.theta).collect());
            for (w, h) in want.iter().zip(&have) {
                assert!(wrap(w - h).abs() < 1e-9, "{r:?}: {want:?} vs {have:?}");
            }
            for a in got.as_slice() {
                assert!((a.sin - a.theta.sin()).abs() < 1e-12);
                assert!((a.cos - a.theta.cos()).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn double_root_is_one_root_flagged_double() {
        // Two pairs of equal roots: the conic touches the circle twice.
        let q = with_roots([0.3, 0.3, -2.0, -2.0], 1.0);
        let got = q.roots();
        let fits: Vec<Fit> = got.iter().map(|(_, f)| f).collect();
        let thetas: Vec<f64> = got.iter().map(|(a, _)| a.theta).collect();
        assert!(thetas.iter().any(|t| (t - 0.3).abs() < 1e-6), "{thetas:?}");
        assert!(thetas.iter().any(|t| (t + 2.0).abs() < 1e-6), "{thetas:?}");
        assert!(fits.iter().all(|&f| f == Fit::Exact || f == Fit::Double));
    }

    #[test]
    fn no_real_root_gives_the_nearest_as_least_squares() {
        // Q = 2 + cos θ: no root; nearest at θ = π.
        let q = TrigQuadratic {
            c0: 2.0,
            c1: 1.0,
            s1: 0.0,
            c2: 0.0,
            s2: 0.0,
        };
        let got = q.roots();
        let [(root, fit)] = got.iter().collect::<Vec<_>>()[..] else {
            panic!("{got:?}");
        };
        assert_eq!(fit, Fit::LeastSquares);
        assert!(wrap(root.theta - PI).abs() < 1e-6, "{got:?}");
    }

    #[test]
    fn zero_polynomial_has_no_roots() {
        let q = TrigQuadratic {
            c0: 0.0,
            c1: 0.0,
            s1: 0.0,
            c2: 0.0,
            s2: 0.0,
        };
        assert!(q.roots().is_empty());
    }

    #[test]
    fn quartic_factors_match_known_roots() {
        // (t − 1)(t + 2)(t² + 1): two real roots and ±i.
        // = (t² + t − 2)(t² + 1) = t⁴ + t³ − t² + t − 2
        let r = quartic([1.0, -1.0, 1.0, -2.0]);
        let mut real: Vec<f64> = r.iter().filter(|x| x.1 == 0.0).map(|x| x.0).collect();
        real.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(real.len(), 2);
        assert!((real[0] + 2.0).abs() < 1e-14 && (real[1] - 1.0).abs() < 1e-14);
    }
}
