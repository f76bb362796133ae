//! **The S-R-S arm by its arm angle** (KUKA iiwa, DLR LWR): seven revolute joints, axes
//! 1, 2, 3 meeting at the shoulder `S`, axes 5, 6, 7 at the wrist `W`, joint 4 the elbow.
//! Its self-motion turns the elbow about the shoulder–wrist line; the **arm angle** `ψ`
//! says where (Shimizu et al., IEEE T-RO 2008; Faria et al., MMT 2018), and each of the
//! eight global configurations — the signs of q2, q4, q6 — is a closed form of `ψ`:
//!
//! 1. wrist centre `W = p0T − R07 (pT − W0)`, `d = W − S`, `u = d / ‖d‖`
//! 2. q4 — SP3: `‖(E0 − S) + rot(h4, q4) (W0 − E0)‖ = ‖d‖` (joints 1–3 turn about `S`),
//!    `E0` the point of axis 4 nearest `S` (the elbow)
//! 3. `R03` — the rotation taking the arm's zero-configuration shoulder–wrist vector
//!    `v = (E0 − S) + R4 (W0 − E0)` onto `d` and the elbow's offset from that line onto
//!    the direction `e(ψ) = rot(u, ψ) e1`
//! 4. (q1, q2, q3) — the shoulder as a spherical wrist on `R03` (SP4, SP1, SP1)
//! 5. (q5, q6, q7) — the wrist on `R47 = (R03 R4)ᵀ R07`.
//!
//! **The reference plane**: `ψ = 0` where the elbow lies in the plane of the
//! shoulder–wrist line and axis 1 on the side `h1` points to (`e1` = the part of `h1`
//! orthogonal to `u`, normalised); `ψ` turns right-handed about `u` (from the shoulder to
//! the wrist). The parametrisation is singular where the shoulder–wrist line runs along
//! axis 1 (`e1` undefined: the solutions are then flagged singular, `e1` taken orthogonal
//! to `u` by a fixed rule) and where the elbow lies on the line (arm stretched: every `ψ`
//! is the same configuration).
//!
//! Since `R03(ψ) = rot(u, ψ) R03(0)`, every entry of `R03` and of `R47` is
//! `a sin ψ + b cos ψ + c`; for an S-R-S arm whose shoulder and wrist are orthogonal
//! (`h1 ∥ h3 ⟂ h2`, `h5 ∥ h7 ⟂ h6`: the iiwa) so are the sine and cosine of every joint
//! up to a positive factor, and a joint meets a limit `L` where `a sin ψ + b cos ψ + c = 0`
//! ([`arm_angle_intervals`]): the intervals of `ψ` inside the limits are exact.

use super::wrist::Wrist;
use super::WristPair;
use crate::ik::geometry::{flat, meet, orthogonal, rot, Geometry, Pose, M3, V3};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp3, wrap, Fit};
use crate::math::{acos, atan2, sqrt};
use core::f64::consts::PI;

/// `|flat(u, ·)|²` below which a direction counts as along `u`.
const ALONG: f64 = 1e-20;

/// An S-R-S arm's geometry, set up once per call.
struct Srs {
    s: V3,
    w0: V3,
    e0: V3,
    h: [V3; 7],
    shoulder: Wrist,
    wrist: Wrist,
}

impl Srs {
    fn new(g: &Geometry<7>, pair: WristPair) -> Srs {
        let s = meet(g, 0, 1);
        let w0 = meet(g, 4, 5);
        let (h4, p4) = (g.h[3], g.p[3]);
        let e0 = p4 + h4 * h4.dot(&(s - p4));
        Srs {
            s,
            w0,
            e0,
            h: g.h,
            shoulder: Wrist::of_axes([g.h[0], g.h[1], g.h[2]], pair),
            wrist: Wrist::of_axes([g.h[4], g.h[5], g.h[6]], pair),
        }
    }

    /// `R07` and the wrist centre at the target.
    fn target(&self, g: &Geometry<7>, pose: &Pose) -> (M3, V3) {
        let r07 = pose.r * g.r_tool.transpose();
        (r07, pose.p - r07 * (g.p_tool - self.w0))
    }

    /// The unit shoulder–wrist direction and the reference direction `e1` (with whether
    /// it is defined: the line not along axis 1).
    fn line(&self, w: &V3) -> (V3, V3, bool) {
        let u = (w - self.s).normalize();
        let e = flat(&u, &self.h[0]);
        if e.norm_squared() > ALONG {
            (u, e.normalize(), true)
        } else {
            (u, orthogonal(&u).normalize(), false)
        }
    }

    /// `R03` at `ψ = 0` for the elbow `q4` (its rotation `r4`): the zero configuration's
    /// shoulder–wrist vector onto `u`, the elbow's offset onto `e1`; `None` when the
    /// elbow lies on the line (every `ψ` the same).
    fn r03_at_zero(&self, r4: &M3, u: &V3, e1: &V3) -> Option<M3> {
        let a = self.e0 - self.s;
        let v = a + r4 * (self.w0 - self.e0);
        let vn = v.normalize();
        let off = flat(&vn, &a);
        if off.norm_squared() <= ALONG * a.norm_squared().max(1e-300) {
            return None;
        }
        let ev = off.normalize();
        let from = M3::from_columns(&[vn, ev, vn.cross(&ev)]);
        let to = M3::from_columns(&[*u, *e1, u.cross(e1)]);
        Some(to * from.transpose())
    }

    /// The two roots of q4 (SP3), with their fit.
    fn elbow(&self, w: &V3, free: f64) -> crate::ik::subproblems::Roots {
        let h4 = self.h[3];
        sp3(
            &(self.w0 - self.e0),
            &(self.s - self.e0),
            &h4,
            (w - self.s).norm(),
            free,
        )
    }
}

/// All solutions of `pose` whose arm angle is `psi` (see the module docs): up to eight,
/// one per global configuration, pushed into `out`. `free` gives the joints a singular
/// pose leaves undetermined.
pub fn srs_arm_angle(
    g: &Geometry<7>,
    pose: &Pose,
    psi: f64,
    pair: WristPair,
    free: &[f64; 7],
    out: &mut Candidates<7, 8>,
) {
    let srs = Srs::new(g, pair);
    let (r07, w) = srs.target(g, pose);
    let (u, e1, defined) = srs.line(&w);
    let line_fit = if defined { Fit::Exact } else { Fit::Free };
    let turn = rot(&u, psi);
    let t4 = srs.elbow(&w, free[3]);
    for q4 in t4.as_slice() {
        let r4 = q4.rot(&srs.h[3]);
        let (r03, fit4) = match srs.r03_at_zero(&r4, &u, &e1) {
            Some(r) => (turn * r, t4.fit.and(line_fit)),
            // Stretched: the elbow on the line, ψ has no meaning; any R03 that takes v
            // onto d (the reference one with an arbitrary offset direction).
            None => {
                let a = srs.e0 - srs.s;
                let v = a + r4 * (srs.w0 - srs.e0);
                let vn = v.normalize();
                let ev = orthogonal(&vn).normalize();
                let from = M3::from_columns(&[vn, ev, vn.cross(&ev)]);
                let to = M3::from_columns(&[u, e1, u.cross(&e1)]);
                (turn * to * from.transpose(), t4.fit.and(Fit::Free))
            }
        };
        let mut sh = [([0.0; 3], Fit::Exact); 2];
        let n = srs.shoulder.solve(
            srs.shoulder.target(&r03),
            || r03,
            [free[0], free[2]],
            &mut sh,
        );
        let r47 = (r03 * r4).transpose() * r07;
        let mut wr = [([0.0; 3], Fit::Exact); 2];
        let m = srs
            .wrist
            .solve(srs.wrist.target(&r47), || r47, [free[4], free[6]], &mut wr);
        for &(q123, f123) in &sh[..n] {
            for &(q567, f567) in &wr[..m] {
                let q = [
                    q123[0], q123[1], q123[2], q4.theta, q567[0], q567[1], q567[2],
                ];
                out.push(q, fit4.and(f123).and(f567));
            }
        }
    }
}

/// The arm angle of configuration `q` (see the module docs), in `(−π, π]`; `None` where
/// it is not defined: the shoulder–wrist line along axis 1, or the elbow on the line.
pub fn arm_angle(g: &Geometry<7>, q: &[f64; 7]) -> Option<f64> {
    let srs = Srs::new(g, WristPair::Solve);
    let r03 = rot(&g.h[0], q[0]) * rot(&g.h[1], q[1]) * rot(&g.h[2], q[2]);
    let r4 = rot(&g.h[3], q[3]);
    let w = srs.s + r03 * ((srs.e0 - srs.s) + r4 * (srs.w0 - srs.e0));
    let e = srs.s + r03 * (srs.e0 - srs.s);
    let (u, e1, defined) = srs.line(&w);
    let x = flat(&u, &(e - srs.s));
    if !defined || x.norm_squared() <= ALONG * (e - srs.s).norm_squared().max(1e-300) {
        return None;
    }
    Some(atan2(u.dot(&e1.cross(&x)), e1.dot(&x)))
}

/// A global configuration of an S-R-S arm: the signs of q2, q4 and q6 (`true`: ≥ 0).
pub type Configuration = [bool; 3];

/// The configuration of `q`.
pub fn configuration(q: &[f64; 7]) -> Configuration {
    [wrap(q[1]) >= 0.0, wrap(q[3]) >= 0.0, wrap(q[5]) >= 0.0]
}

/// Up to 16 closed intervals `[ψ_lo, ψ_hi]` within `[−π, π]` (the last may end at `π`
/// and the first start at `−π`: the same angle, an interval across it is split there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmAngleIntervals {
    items: [[f64; 2]; 16],
    len: usize,
}

impl ArmAngleIntervals {
    /// The intervals, in increasing order.
    pub fn as_slice(&self) -> &[[f64; 2]] {
        &self.items[..self.len]
    }

    /// Whether `psi` lies in one of them.
    pub fn contains(&self, psi: f64) -> bool {
        self.as_slice()
            .iter()
            .any(|&[lo, hi]| psi >= lo && psi <= hi)
    }

    fn push(&mut self, lo: f64, hi: f64) {
        if self.len > 0 && self.items[self.len - 1][1] >= lo {
            self.items[self.len - 1][1] = hi;
        } else if self.len < self.items.len() {
            self.items[self.len] = [lo, hi];
            self.len += 1;
        }
    }
}

/// `a sin ψ + b cos ψ + c` as `[a, b, c]`, from a linear functional of `R(ψ) = rot(u, ψ)
/// R(0)`: its values on the three parts `R(0) − u uᵀ R(0)` (× cos ψ), `[u]× R(0)`
/// (× sin ψ), `u uᵀ R(0)` (× 1).
type Wave = [f64; 3];

fn wave(parts: &[M3; 3], f: impl Fn(&M3) -> f64) -> Wave {
    [f(&parts[1]), f(&parts[0]), f(&parts[2])]
}

/// The ψ in `[−π, π]` where `a sin ψ + b cos ψ + c = 0`, into `out`.
fn zeros([a, b, c]: Wave, out: &mut [f64; 64], n: &mut usize) {
    let r = sqrt(a * a + b * b);
    if r <= 1e-300 || c.abs() > r {
        return;
    }
    // a sin ψ + b cos ψ = r cos(ψ − φ), φ = atan2(a, b).
    let phi = atan2(a, b);
    let d = acos((-c / r).clamp(-1.0, 1.0));
    for psi in [wrap(phi + d), wrap(phi - d)] {
        if *n < out.len() {
            out[*n] = psi;
            *n += 1;
        }
    }
}

/// A spherical group `rot(a, θa) rot(b, θb) rot(c, θc) = R(ψ)` with `a ∥ c ⟂ b` (the
/// iiwa's shoulder or wrist) in one global configuration (`sb`, the sign of `θb`): each
/// joint's cosine and sine as waves of ψ. With `σ = a·c`: `cos θb = σ aᵀ R c`; with
/// `x = b × c` (⟂ a), `R c` off a is `sin θb rot(a, θa) x`, so `(sin θa, cos θa) ∝ sb ((a ×
/// x)·R c, x·R c)`; with `x' = b × a` (⟂ c), `Rᵀ a` off c is `−sin θb rot(c, −θc) x'`, so
/// `(sin θc, cos θc) ∝ sb ((c × x')·Rᵀ a, −x'·Rᵀ a)` — the factor `|sin θb|` is positive.
struct Spherical {
    /// `cos θb`.
    cos_b: Wave,
    /// `(sin θa, cos θa)` and `(sin θc, cos θc)`, up to the same positive factor each.
    outer: [[Wave; 2]; 2],
    sb: f64,
}

impl Spherical {
    fn new(parts: &[M3; 3], [a, b, c]: [V3; 3], sb: f64) -> Spherical {
        let sigma = a.dot(&c).signum();
        let (x, xp) = (b.cross(&c), b.cross(&a));
        let (y, yp) = (a.cross(&x), c.cross(&xp));
        Spherical {
            cos_b: wave(parts, |m| sigma * a.dot(&(m * c))),
            outer: [
                [
                    wave(parts, |m| sb * y.dot(&(m * c))),
                    wave(parts, |m| sb * x.dot(&(m * c))),
                ],
                [
                    wave(parts, |m| sb * yp.dot(&(m.transpose() * a))),
                    wave(parts, |m| -sb * xp.dot(&(m.transpose() * a))),
                ],
            ],
            sb,
        }
    }

    /// Where a joint meets a limit `L` (`lsc`: each limit's sine and cosine): `cos θb =
    /// cos L` (the middle joint), `sin θ cos L − cos θ sin L = 0` (the outer ones); the
    /// mirror images these also catch only split an interval.
    fn cuts(&self, lsc: &[[(f64, f64); 2]; 3], cuts: &mut [f64; 64], n: &mut usize) {
        for (_, cl) in lsc[1] {
            if cl.is_finite() {
                let mut f = self.cos_b;
                f[2] -= cl;
                zeros(f, cuts, n);
            }
        }
        for (k, [s, c]) in [(0, self.outer[0]), (2, self.outer[1])] {
            for (sl, cl) in lsc[k] {
                if sl.is_finite() {
                    zeros(core::array::from_fn(|i| s[i] * cl - c[i] * sl), cuts, n);
                }
            }
        }
    }

    /// Joint `k`'s (0, 1, 2: θa, θb, θc) sine and cosine, up to a positive factor, at the
    /// arm angle whose sine and cosine are `sc`.
    fn sin_cos(&self, k: usize, (s, c): (f64, f64)) -> (f64, f64) {
        let at = |[a, b, k]: Wave| a * s + b * c + k;
        match k {
            1 => {
                let cb = at(self.cos_b).clamp(-1.0, 1.0);
                (self.sb * sqrt(1.0 - cb * cb), cb)
            }
            _ => {
                let [ws, wc] = self.outer[k / 2];
                (at(ws), at(wc))
            }
        }
    }
}

/// Whether the angle whose sine and cosine are `(s, c)` (up to a positive factor) lies in
/// `[lo, hi]` after whole turns, from `lsc` = their sines and cosines — signs only, no
/// arctangent: with `w = hi − lo`, `sin(θ − lo) ≥ 0` and `sin(hi − θ) ≥ 0` when `w ≤ π`,
/// either of them when `π < w < 2π`.
fn inside_limits((s, c): (f64, f64), [lo, hi]: [f64; 2], lsc: &[(f64, f64); 2]) -> bool {
    let w = hi - lo;
    if !w.is_finite() || w >= core::f64::consts::TAU {
        return true;
    }
    let [(sl, cl), (sh, ch)] = *lsc;
    let after_lo = s * cl - c * sl >= 0.0;
    let before_hi = c * sh - s * ch >= 0.0;
    if w <= PI {
        after_lo && before_hi
    } else {
        after_lo || before_hi
    }
}

/// The exact intervals of arm angle in which configuration `config` of `pose` has every
/// joint within `limits` (empty when the pose is out of reach for it, or q4 is outside
/// its limits). For an S-R-S arm with an orthogonal shoulder and wrist (the engine
/// decides it; see the module docs): each joint meets each limit where a sinusoid of ψ
/// vanishes; between those angles (and their mirror images, which only split an
/// interval) a joint stays on one side, decided at the midpoint from the signs of the
/// same sinusoids at the limits (no solve per piece).
pub fn arm_angle_intervals(
    g: &Geometry<7>,
    pose: &Pose,
    config: Configuration,
    limits: &[[f64; 2]; 7],
) -> ArmAngleIntervals {
    let mut out = ArmAngleIntervals {
        items: [[0.0; 2]; 16],
        len: 0,
    };
    let srs = Srs::new(g, WristPair::Solve);
    let (r07, w) = srs.target(g, pose);
    let (u, e1, _) = srs.line(&w);
    let t4 = srs.elbow(&w, 0.0);
    let Some(q4) = t4
        .as_slice()
        .iter()
        .find(|a| (wrap(a.theta) >= 0.0) == config[1])
    else {
        return out;
    };
    if t4.fit == Fit::LeastSquares || !within(q4.theta, limits[3]) {
        return out;
    }
    let r4 = q4.rot(&srs.h[3]);
    let Some(r0) = srs.r03_at_zero(&r4, &u, &e1) else {
        return out;
    };
    // R03(ψ) and R47(ψ) = R4ᵀ R03(ψ)ᵀ R07 in parts (cos, sin, 1).
    let uu = u * u.transpose();
    let ux = u.cross_matrix();
    let shoulder = [r0 - uu * r0, ux * r0, uu * r0];
    let wrist = shoulder.map(|p| r4.transpose() * p.transpose() * r07);
    let h = &srs.h;
    let sign = |b: bool| if b { 1.0 } else { -1.0 };
    let groups = [
        Spherical::new(&shoulder, [h[0], h[1], h[2]], sign(config[0])),
        Spherical::new(&wrist, [h[4], h[5], h[6]], sign(config[2])),
    ];
    let joints = [[0, 1, 2], [4, 5, 6]];
    // Each limit's sine and cosine, once (non-finite for a joint without limits).
    let lsc: [[(f64, f64); 2]; 7] = core::array::from_fn(|i| {
        limits[i].map(|l| {
            if l.is_finite() {
                crate::math::sin_cos(l)
            } else {
                (f64::NAN, f64::NAN)
            }
        })
    });
    let mut cuts = [0.0; 64];
    let mut n = 0;
    for (s, j) in groups.iter().zip(joints) {
        s.cuts(&j.map(|i| lsc[i]), &mut cuts, &mut n);
    }
    // Sort the cuts with the ends of [−π, π]; test each piece at its midpoint, where
    // every joint is read off its waves (q4 is the same for every ψ).
    let cuts = &mut cuts[..n];
    cuts.sort_unstable_by(f64::total_cmp);
    let mut edges = [0.0; 66];
    edges[0] = -PI;
    edges[1..=n].copy_from_slice(cuts);
    edges[n + 1] = PI;
    let inside = |psi: f64| {
        let sc = crate::math::sin_cos(psi);
        groups
            .iter()
            .zip(joints)
            .all(|(s, j)| (0..3).all(|k| inside_limits(s.sin_cos(k, sc), limits[j[k]], &lsc[j[k]])))
    };
    for k in 0..=n {
        let (lo, hi) = (edges[k], edges[k + 1]);
        if hi > lo && inside(0.5 * (lo + hi)) {
            out.push(lo, hi);
        }
    }
    out
}

/// `θ` within `[lo, hi]` after a whole turn either way.
fn within(theta: f64, [lo, hi]: [f64; 2]) -> bool {
    use core::f64::consts::TAU;
    [theta, theta + TAU, theta - TAU]
        .iter()
        .any(|&t| t >= lo && t <= hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::geometry::V3;

    /// The KUKA iiwa 14 at q = 0 (modified DH: d1 0.36, d3 0.42, d5 0.4, d7 0.126).
    fn iiwa() -> Geometry<7> {
        let (z, y) = (V3::z(), V3::y());
        let at = |h: f64| V3::new(0.0, 0.0, h);
        Geometry {
            h: [z, y, z, -y, z, y, z],
            p: [
                at(0.36),
                at(0.36),
                at(0.78),
                at(0.78),
                at(1.18),
                at(1.18),
                at(1.18),
            ],
            prismatic: [false; 7],
            r_tool: M3::identity(),
            p_tool: at(1.306),
        }
    }

    fn gap(a: &[f64; 7], b: &[f64; 7]) -> f64 {
        (0..7).map(|i| wrap(a[i] - b[i]).abs()).fold(0.0, f64::max)
    }

    #[test]
    fn every_configuration_at_the_arm_angle_reaches_the_pose() {
        let g = iiwa();
        let q = [0.4, 0.7, -0.3, 1.2, 0.5, -0.9, 0.2];
        let pose = g.fk(&q);
        let psi = arm_angle(&g, &q).unwrap();
        let mut out = Candidates::default();
        srs_arm_angle(&g, &pose, psi, WristPair::HalfTurn, &[0.0; 7], &mut out);
        assert_eq!(out.as_slice().len(), 8);
        let mut configs = [false; 8];
        for c in out.as_slice() {
            let t = g.fk(&c.q);
            assert!(
                (t.r - pose.r).norm() < 1e-12 && (t.p - pose.p).norm() < 1e-12,
                "{c:?}"
            );
            assert!(wrap(arm_angle(&g, &c.q).unwrap() - psi).abs() < 1e-12);
            let k = configuration(&c.q);
            configs[usize::from(k[0]) * 4 + usize::from(k[1]) * 2 + usize::from(k[2])] = true;
        }
        assert!(configs.iter().all(|&x| x), "one solution per configuration");
        assert!(out.as_slice().iter().any(|c| gap(&c.q, &q) < 1e-9));
        // Another arm angle: the same eight, turned.
        let mut other = Candidates::default();
        srs_arm_angle(
            &g,
            &pose,
            psi + 1.0,
            WristPair::Solve,
            &[0.0; 7],
            &mut other,
        );
        assert_eq!(other.as_slice().len(), 8);
        for c in other.as_slice() {
            assert!(wrap(arm_angle(&g, &c.q).unwrap() - psi - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn the_intervals_end_where_a_joint_meets_its_limit() {
        let g = iiwa();
        let d = core::f64::consts::PI / 180.0;
        let limits = [
            [-170.0 * d, 170.0 * d],
            [-120.0 * d, 120.0 * d],
            [-170.0 * d, 170.0 * d],
            [-120.0 * d, 120.0 * d],
            [-170.0 * d, 170.0 * d],
            [-120.0 * d, 120.0 * d],
            [-175.0 * d, 175.0 * d],
        ];
        let q = [0.4, 0.7, -0.3, 1.2, 0.5, -0.9, 0.2];
        let pose = g.fk(&q);
        let config = configuration(&q);
        let iv = arm_angle_intervals(&g, &pose, config, &limits);
        assert!(!iv.as_slice().is_empty());
        assert!(iv.contains(arm_angle(&g, &q).unwrap()));
        let ok = |psi: f64| {
            let mut c = Candidates::default();
            srs_arm_angle(&g, &pose, psi, WristPair::Solve, &[0.0; 7], &mut c);
            c.as_slice()
                .iter()
                .any(|k| configuration(&k.q) == config && (0..7).all(|i| within(k.q[i], limits[i])))
        };
        for &[lo, hi] in iv.as_slice() {
            if lo > -PI {
                assert!(ok(lo + 1e-7) && !ok(lo - 1e-7), "{lo}");
            }
            if hi < PI {
                assert!(ok(hi - 1e-7) && !ok(hi + 1e-7), "{hi}");
            }
        }
    }
}
