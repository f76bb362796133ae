//! **The arm with a pitching wrist, and a roll** — four or five revolute joints: a base
//! joint, then three parallel axes (h2 ∥ h3 ∥ h4: shoulder, elbow, wrist pitch), and with
//! five a roll whose axis carries the tool point (the Interbotix WidowX 250, the KUKA
//! youBot arm, the Lynxmotion AL5D; with four, the ROBOTIS OpenManipulator-X, the PincherX
//! 100).
//!
//! Such an arm reaches a 4- (5-) dimensional set of poses, not every pose: the tool point
//! anywhere in reach, the approach — the direction the pitch turns, `a = R0T RTᵀ v`, with
//! `v = h5` for five joints and `v ⟂ h1, h2` for four — only within the arm's plane, whose
//! azimuth the position fixes, and with five joints any roll about it. So the solver puts
//! the **position** first: the tool point is reached wherever it can be; the approach is
//! met exactly when the pose lies in the arm's set and is otherwise the nearest direction
//! in the arm's plane (the branch is then least squares, flagged inexact by its residual);
//! the roll follows from the target's orientation. A pose made by the arm's own `fk` is
//! reached exactly by every branch that reaches its point.

use crate::ik::geometry::{Angle, Geometry, Pose, M3, V3};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp1, sp1_angle, sp2, sp3, sp4, wrap, Fit, MERGE_DISTANCE};

/// **h2 ∥ h3 ∥ h4 after h1, with five joints the tool point on axis 5** (`N` = 4 or 5;
/// `d = p − p1`, `R = R0T RTᵀ`, `θ = q2 ± q3 ± q4` the turn about the parallel axes, signs
/// from their senses):
///
/// 1. q1 — SP4: `h2ᵀ rot(−h1, q1) d = h2ᵀ (pT − p1)` (joints 2–5 keep the tool point's
///    component along h2; two roots: the arm's plane, reached facing either way). With
///    the tool point on axis 1 that leaves q1 free, and (q1, θ) — SP2: `rot(−h1, q1) R v
///    = rot(h2, θ) v` — come from the approach instead. Where the two planes merge (the
///    tool point on the cylinder about axis 1 its offset along h2 draws: a double root,
///    placed only to ~3e-6 rad), the arm is not singular — the approach still fixes q1 —
///    so q1 is the root of the approach's SP4, `h2ᵀ rot(−h1, q1) R v = h2ᵀ v`, nearest to
///    it, and the branch is checked on `fk` ([`Fit::Checked`]).
/// 2. θ — SP1: `rot(h2, θ) v = rot(−h1, q1) R v` (least squares where the approach leaves
///    the arm's plane). With four joints the whole rotation must match: θ is the turn
///    about h2 nearest to `rot(−h1, q1) R` over a basis of the plane ⟂ h2, and each
///    branch is checked on `fk` ([`Fit::Checked`]).
/// 3. q5 (five joints) — SP1: `rot(h5, q5) x = rot(h2, −θ) rot(−h1, q1) R x`, `x ⟂ h5`.
/// 4. q3 — SP3: `‖p23 + rot(h3, q3) p34‖ = ‖w‖`, `w = rot(−h1, q1) d − p12 − rot(h2, θ)
///    (pT − p4)` (rot(h5, q5) leaves `pT − p5` alone); two roots, elbow up and down.
/// 5. q2 — SP1: `rot(h2, q2) (p23 + R3 p34) = w`; q4 from θ.
///
/// Up to four solutions.
pub fn pitch_roll<const N: usize, const K: usize>(
    g: &Geometry<N>,
    pose: &Pose,
    free: &[f64; N],
    out: &mut Candidates<N, K>,
) {
    let [h1, h2, h3, h4] = [g.h[0], g.h[1], g.h[2], g.h[3]];
    let (s3, s4) = (h3.dot(&h2).signum(), h4.dot(&h2).signum());
    let roll = N == 5;
    let (p12, p23, p34, p4t) = (
        g.p[1] - g.p[0],
        g.p[2] - g.p[1],
        g.p[3] - g.p[2],
        g.p_tool - g.p[3],
    );
    // The direction the pitch turns and the roll leaves alone.
    let v = if roll {
        g.h[4]
    } else {
        h2.cross(&h1).normalize()
    };
    let r = pose.r * g.r_tool.transpose();
    let (d, a) = (pose.p - g.p[0], r * v);
    // Four joints: the whole rotation `rot(h1, q1) rot(h2, θ)` is the target's, so a
    // branch is exact only if it is, which one direction does not show (`R v ∥ h1` leaves
    // q1 out of it): θ from a basis of the plane ⟂ h2, and the branch checked on `fk`.
    let basis = [v, h2.cross(&v)];
    let pitch_fit = if roll { Fit::Exact } else { Fit::Checked };
    let theta_free = free[1] + s3 * free[2] + s4 * free[3];
    let t1 = sp4(&h2, &d, &(-h1), h2.dot(&(g.p_tool - g.p[0])), free[0]);
    // (q1, θ, fit) per arm plane: from the position, or (the tool point on axis 1) from
    // the approach.
    let mut planes = [(Angle::new(0.0), None, Fit::Exact); 2];
    let n = if t1.fit == Fit::Free {
        // Of the basis, the direction the target turns farthest from axis 1.
        let x = if roll || h1.dot(&(r * v)).abs() <= h1.dot(&(r * basis[1])).abs() {
            v
        } else {
            basis[1]
        };
        let (pairs, n, fit) = sp2(&(r * x), &x, &(-h1), &h2, (free[0], theta_free));
        // The two arm planes met (the Jacobian's position rows lost axis 1): exact, but
        // at a singular configuration, as a double root is.
        for (slot, (q1, t)) in planes.iter_mut().zip(&pairs[..n]) {
            *slot = (*q1, Some(*t), fit.and(pitch_fit).and(Fit::Double));
        }
        n
    } else if let (1, Fit::Double | Fit::LeastSquares) = (t1.n, t1.fit) {
        planes[0] = match facing(&h1, &h2, &a, &v, t1.angles[0]) {
            Some(q1) => (q1, None, Fit::Checked),
            None => (t1.angles[0], None, t1.fit),
        };
        1
    } else {
        for (slot, q1) in planes.iter_mut().zip(t1.as_slice()) {
            *slot = (*q1, None, t1.fit);
        }
        t1.n
    };
    for &(q1, theta, fit1) in &planes[..n] {
        let r1 = q1.rot(&h1);
        let (t, ft) = match theta {
            Some(t) => (t, Fit::Exact),
            None if roll => sp1_angle(&v, &r1.tr_mul(&a), &h2, theta_free),
            None => (pitch(&h2, &basis, &r1.tr_mul(&r)), Fit::Checked),
        };
        let rt = t.rot(&h2);
        let (q5, f5) = if roll {
            let h5 = g.h[4];
            let x = h5.cross(&h2);
            sp1(&x, &rt.tr_mul(&r1.tr_mul(&(r * x))), &h5, free[4])
        } else {
            (0.0, Fit::Exact)
        };
        let w = r1.tr_mul(&d) - p12 - rt * p4t;
        let t3 = sp3(&p34, &(-p23), &h3, w.norm(), free[2]);
        for q3 in t3.as_slice() {
            let arm: V3 = p23 + q3.rot(&h3) * p34;
            let (q2, f2) = sp1(&arm, &w, &h2, free[1]);
            let mut q = [0.0; N];
            q[0] = q1.theta;
            q[1] = q2;
            q[2] = q3.theta;
            q[3] = wrap(s4 * (t.theta - q2 - s3 * q3.theta));
            if roll {
                q[4] = q5;
            }
            out.push(q, fit1.and(ft).and(f5).and(t3.fit).and(f2));
        }
    }
}

/// Where the position leaves the arm's plane at a double root `merged` (see step 1 of
/// [`pitch_roll`]): the root of `h2ᵀ rot(−h1, q1) a = h2ᵀ v` — the approach `a` in the
/// plane — within [`MERGE_DISTANCE`] of it, if the approach has two distinct roots (else,
/// or if neither is that near, the pose is off the arm's set there: `None`).
#[inline]
fn facing(h1: &V3, h2: &V3, a: &V3, v: &V3, merged: Angle) -> Option<Angle> {
    let t = sp4(h2, a, &(-h1), h2.dot(v), merged.theta);
    if t.fit != Fit::Exact {
        return None;
    }
    let off = |q: &Angle| wrap(q.theta - merged.theta).abs();
    t.as_slice()
        .iter()
        .copied()
        .filter(|q1| off(q1) <= MERGE_DISTANCE)
        .min_by(|x, y| off(x).total_cmp(&off(y)))
}

/// The rotation about `k` nearest to `m` (least squares over the orthonormal `basis` of
/// the plane ⟂ `k`): `θ = atan2(Σ kᵀ (x × m x), Σ xᵀ m x)`.
#[inline]
fn pitch(k: &V3, basis: &[V3; 2], m: &M3) -> Angle {
    let (mut s, mut c) = (0.0, 0.0);
    for x in basis {
        let y = m * x;
        s += k.dot(&x.cross(&y));
        c += x.dot(&y);
    }
    Angle::atan2(s, c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::geometry::rot;
    use crate::ik::solutions::EXACT_TOLERANCE;
    use core::f64::consts::FRAC_PI_2;

    /// A WidowX-like arm: waist about z, shoulder, elbow and wrist about y, the roll about
    /// x carrying the tool point; the wrist-to-tool length equals the upper arm's, so the
    /// configuration `(q1, 0, π/2, π/2, q5)` folds the tool point back onto axis 1.
    fn arm() -> Geometry<5> {
        let (x, y, z) = (V3::x(), V3::y(), V3::z());
        Geometry {
            h: [z, y, y, y, x],
            p: [
                V3::zeros(),
                V3::new(0.0, 0.0, 0.1),
                V3::new(0.3, 0.0, 0.1),
                V3::new(0.5, 0.0, 0.1),
                V3::new(0.6, 0.0, 0.1),
            ],
            prismatic: [false; 5],
            r_tool: rot(&y, 0.4),
            p_tool: V3::new(0.8, 0.0, 0.1),
        }
    }

    fn solved(g: &Geometry<5>, pose: &Pose, free: &[f64; 5]) -> Candidates<5, 4> {
        let mut out = Candidates::default();
        pitch_roll(g, pose, free, &mut out);
        out
    }

    fn gap(a: &[f64; 5], b: &[f64; 5]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| wrap(x - y).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_tool_point_on_axis_1_takes_q1_from_the_approach() {
        let g = arm();
        let q = [0.7, 0.0, FRAC_PI_2, FRAC_PI_2, 0.3];
        let pose = g.fk(&q);
        assert!(pose.p.x.hypot(pose.p.y) < 1e-15, "{:?}", pose.p);
        // Not the configuration as the free values: q1 must come from the approach.
        let out = solved(&g, &pose, &[0.0; 5]);
        let found = out.as_slice().iter().find(|c| gap(&c.q, &q) <= 1e-12);
        let c = found.unwrap_or_else(|| panic!("{q:?} not among {:?}", out.as_slice()));
        assert_eq!(c.fit, Fit::Double);
        for c in out.as_slice().iter().filter(|c| c.fit == Fit::Double) {
            let t = g.fk(&c.q);
            assert!((t.p - pose.p).norm() <= 1e-15 && (t.r - pose.r).norm() <= 1e-14);
        }
    }

    /// Where the tool point lies on the cylinder about axis 1 that its offset along h2
    /// draws, the two arm planes of step 1 merge (a double root, placed to ~3e-6 rad), but
    /// the arm is not singular there: the approach fixes q1, and the branch reaches the
    /// pose (it came ~1e-6 rad off, a least-squares branch missing by ~1e-7, before).
    #[test]
    fn merged_arm_planes_take_q1_from_the_approach() {
        let mut g = arm();
        // The wrist and the tool 0.05 off the arm's plane, along h2: with (q1, 0, π/2,
        // π/2, q5) the tool point lies 0.05 from axis 1, on the cylinder.
        g.p[3].y = 0.05;
        g.p[4].y = 0.05;
        g.p_tool.y = 0.05;
        for dq in [0.0, 1e-9, -1e-9, 1e-7, -1e-7, 2e-6, -2e-6] {
            let q = [0.7, dq, FRAC_PI_2, FRAC_PI_2 - 0.3 * dq, 0.3];
            let pose = g.fk(&q);
            let out = solved(&g, &pose, &[0.0; 5]);
            let found = out.as_slice().iter().find(|c| gap(&c.q, &q) <= 1e-9);
            let c = found.unwrap_or_else(|| panic!("{q:?} not among {:?}", out.as_slice()));
            // Exact as `finish` counts it (the arm reaches 0.8 m).
            let t = g.fk(&c.q);
            let miss = (t.p - pose.p).amax().max((t.r - pose.r).amax());
            assert!(miss <= EXACT_TOLERANCE, "{c:?} misses {pose:?} by {miss:e}");
            // Taken from the approach, checked on fk by `finish`.
            if c.fit != Fit::Exact {
                assert_eq!(c.fit, Fit::Checked, "{c:?}");
            }
        }
    }

    #[test]
    fn a_pose_off_the_arms_set_keeps_its_position() {
        let g = arm();
        let q = [0.7, -0.4, 0.9, -0.3, 0.3];
        let reached = g.fk(&q);
        // The target turned by 0.2 rad about an axis across the arm's plane: its approach
        // leaves the plane.
        let tilt = 0.2;
        let turn = rot(&V3::new(1.0, 0.0, 1.0).normalize(), tilt);
        let pose = Pose {
            r: turn * reached.r,
            p: reached.p,
        };
        let out = solved(&g, &pose, &q);
        assert_eq!(out.as_slice().len(), 4);
        let approach = |r: &M3| r * g.r_tool.transpose() * g.h[4];
        for c in out.as_slice() {
            assert_eq!(c.fit, Fit::LeastSquares, "{c:?}");
            let t = g.fk(&c.q);
            assert!((t.p - pose.p).norm() <= 1e-15, "{c:?}");
            let off = approach(&t.r).angle(&approach(&pose.r));
            assert!(off <= tilt + 1e-12, "{c:?}: approach {off} rad off");
        }
        // The arm's plane the configuration was in is kept, with its elbow.
        assert!(out
            .as_slice()
            .iter()
            .any(|c| gap(&c.q, &q) <= tilt && (c.q[0] - q[0]).abs() <= 1e-12));
    }
}
