//! **Position arms** — three joints that place the tool point (task rows x, y, z; the
//! tool's orientation follows and is not asked for): the elbow arm, the spherical
//! (Stanford-type) arm, the cylindrical arm and the Cartesian gantry. The engine decides
//! at expansion time, exactly, which of the five cases a chain is:
//!
//! | case | condition | steps |
//! |---|---|---|
//! | [`position_intersecting`] | R R R, h1 ∩ h2 | q3 — SP3, (q1, q2) — SP2 |
//! | [`position_parallel`] | R R R, h2 ∥ h3, h1 ∦ h2 | q1 — SP4, q3 — SP3, q2 — SP1 |
//! | [`position_intersecting_prismatic`] | R R P, h1 ∩ h2 | q3 — a quadratic, (q1, q2) — SP2 |
//! | [`position_one_revolute`] | R P P or P P R, the prismatic axes not parallel | the revolute joint — SP4, the others — a 2 × 2 linear system |
//! | [`position_cartesian`] | P P P, axes independent | a 3 × 3 linear system |
//!
//! With `p` the target point, `pT` the tool point at `q = 0`, `pi` a point on axis `i`
//! and `Ri = rot(hi, qi)` (a prismatic joint adds `qi hi` after the rotations before it):
//! `p = p1 + R1 (p2 − p1) + R1 R2 (p3 − p2) + R1 R2 R3 (pT − p3)`.

use crate::ik::geometry::{meet, Angle, Geometry, Pose, M3, V3};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{slide, sp1, sp2, sp3, sp4, Fit};

/// **R R R, h1 ∩ h2** (at `c12`; the anthropomorphic arm without offsets):
///
/// 1. q3 — SP3: `‖(p3 − c12) + R3 (pT − p3)‖ = ‖p − c12‖` (joints 1, 2 turn about c12)
/// 2. (q1, q2) — SP2: `rot(−h1, q1) (p − c12) = rot(h2, q2) ((p3 − c12) + R3 (pT − p3))`
///
/// Up to four solutions; q1 is free when `p` lies on axis 1.
pub fn position_intersecting<const K: usize>(
    g: &Geometry<3>,
    pose: &Pose,
    free: &[f64; 3],
    out: &mut Candidates<3, K>,
) {
    let c12 = meet(g, 0, 1);
    shoulder_elbow(g, c12, g.p_tool, pose.p, free, |q1, q2, q3, _, fit| {
        out.push([q1.theta, q2.theta, q3.theta], fit)
    });
}

/// The point `end` of an arm (at `q = 0`) placed at `target` by its first three joints,
/// revolute, axes 1 and 2 meeting at `c12`: q3 — SP3 (joints 1, 2 keep the distance from
/// c12), (q1, q2) — SP2. Each solution goes to `each(q1, q2, q3, R3, fit)`. The position
/// arm with h1 ∩ h2 (`end` the tool point) and the arm of the spherical-wrist family with
/// h1 ∩ h2 (`end` the wrist centre) are this.
#[inline(always)]
pub(super) fn shoulder_elbow<const N: usize>(
    g: &Geometry<N>,
    c12: V3,
    end: V3,
    target: V3,
    free: &[f64],
    mut each: impl FnMut(&Angle, &Angle, &Angle, &M3, Fit),
) {
    let [h1, h2, h3] = [g.h[0], g.h[1], g.h[2]];
    let (p23, p3e) = (g.p[2] - c12, end - g.p[2]);
    let d = target - c12;
    let t3 = sp3(&p3e, &(-p23), &h3, d.norm(), free[2]);
    for q3 in t3.as_slice() {
        let r3 = q3.rot(&h3);
        let arm = p23 + r3 * p3e;
        let (t12, n, f12) = sp2(&d, &arm, &(-h1), &h2, (free[0], free[1]));
        for (q1, q2) in &t12[..n] {
            each(q1, q2, q3, &r3, t3.fit.and(f12));
        }
    }
}

/// [`shoulder_elbow`] with joint 3 prismatic: q3 — the slide to a distance `‖u + q3 h3‖
/// = ‖target − c12‖`, `u = end − c12`, then (q1, q2) — SP2; each solution to `each(q1,
/// q2, q3, fit)`. The spherical (R R P) position arm and the Stanford arm's first three
/// joints.
#[inline(always)]
pub(super) fn shoulder_slide<const N: usize>(
    g: &Geometry<N>,
    c12: V3,
    end: V3,
    target: V3,
    free: &[f64],
    mut each: impl FnMut(&Angle, &Angle, f64, Fit),
) {
    let [h1, h2, h3] = [g.h[0], g.h[1], g.h[2]];
    let u = end - c12;
    let d = target - c12;
    let (roots, n3, fit) = slide(&u, &h3, d.norm());
    for &q3 in &roots[..n3] {
        let arm = u + h3 * q3;
        let (t12, n, f12) = sp2(&d, &arm, &(-h1), &h2, (free[0], free[1]));
        for (q1, q2) in &t12[..n] {
            each(q1, q2, q3, fit.and(f12));
        }
    }
}

/// **R R R, h2 ∥ h3, h1 ∦ h2** (the elbow arm with a shoulder offset; PUMA's first three
/// joints):
///
/// 1. q1 — SP4: `h2ᵀ rot(−h1, q1) (p − p1) = h2ᵀ (pT − p1)` (R2, R3 keep h2's component)
/// 2. q3 — SP3: `‖(p3 − p2) + R3 (pT − p3)‖ = ‖rot(−h1, q1) (p − p1) − (p2 − p1)‖`
/// 3. q2 — SP1: `rot(h2, q2) ((p3 − p2) + R3 (pT − p3)) = rot(−h1, q1) (p − p1) − (p2 − p1)`
///
/// Up to four solutions.
pub fn position_parallel<const K: usize>(
    g: &Geometry<3>,
    pose: &Pose,
    free: &[f64; 3],
    out: &mut Candidates<3, K>,
) {
    let [h1, h2, h3] = g.h;
    let (p12, p23, p3t) = (g.p[1] - g.p[0], g.p[2] - g.p[1], g.p_tool - g.p[2]);
    let d = pose.p - g.p[0];
    let t1 = sp4(&h2, &d, &(-h1), h2.dot(&(g.p_tool - g.p[0])), free[0]);
    for q1 in t1.as_slice() {
        let reach = q1.rot(&h1).transpose() * d - p12;
        let t3 = sp3(&p3t, &(-p23), &h3, reach.norm(), free[2]);
        for q3 in t3.as_slice() {
            let arm = p23 + q3.rot(&h3) * p3t;
            let (q2, f2) = sp1(&arm, &reach, &h2, free[1]);
            out.push([q1.theta, q2, q3.theta], t1.fit.and(t3.fit).and(f2));
        }
    }
}

/// **R R P, h1 ∩ h2** (at `c12`; the spherical arm, the Stanford arm's first three joints):
///
/// 1. q3 — the slide to a distance: `‖u + q3 h3‖ = ‖p − c12‖`, `u = pT − c12` (two roots)
/// 2. (q1, q2) — SP2: `rot(−h1, q1) (p − c12) = rot(h2, q2) (u + q3 h3)`
///
/// Up to four solutions (the two of q3 on either side of the shoulder).
pub fn position_intersecting_prismatic<const K: usize>(
    g: &Geometry<3>,
    pose: &Pose,
    free: &[f64; 3],
    out: &mut Candidates<3, K>,
) {
    let c12 = meet(g, 0, 1);
    shoulder_slide(g, c12, g.p_tool, pose.p, free, |q1, q2, q3, fit| {
        out.push([q1.theta, q2.theta, q3], fit)
    });
}

/// **One revolute joint and two prismatic, the revolute joint first (R P P, the
/// cylindrical arm) or last (P P R)**, the prismatic axes `a`, `b` not parallel, with
/// `n = a × b / ‖a × b‖`:
///
/// - R P P: `rot(−h1, q1) (p − p1) = (pT − p1) + q2 h2 + q3 h3`; q1 — SP4 on the
///   component along `n`: `nᵀ rot(−h1, q1) (p − p1) = nᵀ (pT − p1)`;
/// - P P R: `(p − p3) − q1 h1 − q2 h2 = R3 (pT − p3)`; q3 — SP4: `nᵀ R3 (pT − p3) = nᵀ
///   (p − p3)`;
///
/// then the prismatic joints from the 2 × 2 system `q_a a + q_b b = v` (its normal
/// equations, exact: `v` has no component along `n`). Up to two solutions; the revolute
/// joint is free when the tool point lies on its axis.
pub fn position_one_revolute<const K: usize>(
    g: &Geometry<3>,
    pose: &Pose,
    revolute_first: bool,
    free: &[f64; 3],
    out: &mut Candidates<3, K>,
) {
    let (r, [i, j]) = if revolute_first {
        (0, [1, 2])
    } else {
        (2, [0, 1])
    };
    let (a, b, h) = (g.h[i], g.h[j], g.h[r]);
    let n = a.cross(&b).normalize();
    let (d, v0) = (pose.p - g.p[r], g.p_tool - g.p[r]);
    let t = if revolute_first {
        sp4(&n, &d, &(-h), n.dot(&v0), free[r])
    } else {
        sp4(&n, &v0, &h, n.dot(&d), free[r])
    };
    for qr in t.as_slice() {
        let v = if revolute_first {
            qr.rot(&h).transpose() * d - v0
        } else {
            d - qr.rot(&h) * v0
        };
        let [qa, qb] = two_slides(&a, &b, &v);
        let mut q = [0.0; 3];
        q[r] = qr.theta;
        q[i] = qa;
        q[j] = qb;
        out.push(q, t.fit);
    }
}

/// **P P P, the axes independent** (the Cartesian gantry): `p − pT = q1 h1 + q2 h2 + q3
/// h3`, one solution by Cramer's rule.
pub fn position_cartesian<const K: usize>(
    g: &Geometry<3>,
    pose: &Pose,
    _free: &[f64; 3],
    out: &mut Candidates<3, K>,
) {
    out.push(cramer(g.h, &(pose.p - g.p_tool)), Fit::Exact);
}

/// `x` with `x1 a + x2 b + x3 c = d` for independent `[a, b, c]` (Cramer's rule).
#[inline]
pub(super) fn cramer([a, b, c]: [V3; 3], d: &V3) -> [f64; 3] {
    let det = a.dot(&b.cross(&c));
    [
        d.dot(&b.cross(&c)) / det,
        d.dot(&c.cross(&a)) / det,
        d.dot(&a.cross(&b)) / det,
    ]
}

/// `(x, y)` with `x a + y b = v` for unit `a ∦ b` and `v` in their plane (the normal
/// equations, solved by Cramer's rule).
fn two_slides(a: &V3, b: &V3, v: &V3) -> [f64; 2] {
    let ab = a.dot(b);
    let (va, vb) = (v.dot(a), v.dot(b));
    let det = 1.0 - ab * ab;
    [(va - ab * vb) / det, (vb - ab * va) / det]
}

/// Tests: each case on random arms of its structure, every solution checked by forward
/// kinematics written out here from the geometry's definition.
#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::*;
    use crate::ik::geometry::rot;
    use crate::ik::XorShift64;

    fn point(rng: &mut XorShift64) -> V3 {
        V3::new(
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
        ) * 2.0
    }

    /// The tool point at `q` (the module docs' formula).
    fn fk(g: &Geometry<3>, q: &[f64; 3]) -> V3 {
        let mut r = M3::identity();
        let mut p = g.p[0];
        let ends = [g.p[1], g.p[2], g.p_tool];
        for i in 0..3 {
            if g.prismatic[i] {
                p += r * g.h[i] * q[i];
            } else {
                r *= rot(&g.h[i], q[i]);
            }
            p += r * (ends[i] - g.p[i]);
        }
        p
    }

    /// A random arm with joints `prismatic`, axes 1 and 2 meeting (`meet`) and axes 2 and 3
    /// antiparallel (`parallel`) where asked, every other relation general.
    fn random(
        rng: &mut XorShift64,
        prismatic: [bool; 3],
        meet: bool,
        parallel: bool,
    ) -> Geometry<3> {
        let mut h = [unit(rng), unit(rng), unit(rng)];
        let mut p = [point(rng), point(rng), point(rng)];
        if parallel {
            h[2] = -h[1];
        }
        if meet {
            p[1] = p[0];
        }
        Geometry {
            h,
            p,
            prismatic,
            r_tool: M3::identity(),
            p_tool: point(rng),
        }
    }

    /// `solve` on 200 random arms made by `arm` and a random `q` each: every solution not
    /// flagged least squares reaches the point (1e-10 of the arm's size), the generating
    /// `q` among them.
    fn check(
        arm: impl Fn(&mut XorShift64) -> Geometry<3>,
        solve: impl Fn(&Geometry<3>, &Pose, &mut Candidates<3, 4>),
    ) {
        let mut rng = XorShift64::new(27);
        for _ in 0..200 {
            let g = arm(&mut rng);
            let q: [f64; 3] = core::array::from_fn(|i| {
                if g.prismatic[i] {
                    2.0 * rng.next_f64() - 1.0
                } else {
                    (2.0 * rng.next_f64() - 1.0) * core::f64::consts::PI
                }
            });
            let pose = Pose {
                r: M3::identity(),
                p: fk(&g, &q),
            };
            let mut out = Candidates::default();
            solve(&g, &pose, &mut out);
            let size = 1.0 + pose.p.norm() + g.p_tool.norm();
            // A branch whose subproblem has no exact root is flagged least squares (the
            // generated code's `finish` then measures it); every other must reach the point.
            for c in out.as_slice().iter().filter(|c| c.fit != Fit::LeastSquares) {
                let e = (fk(&g, &c.q) - pose.p).norm();
                assert!(e <= 1e-10 * size, "{e:e} off: {g:?} {q:?} {:?}", c.q);
            }
            let same = out.as_slice().iter().any(|c| {
                c.fit != Fit::LeastSquares
                    && (0..3).all(|i| {
                        let d = c.q[i] - q[i];
                        let d = if g.prismatic[i] {
                            d
                        } else {
                            crate::ik::subproblems::wrap(d)
                        };
                        d.abs() < 1e-7
                    })
            });
            assert!(same, "generating q not found: {g:?} {q:?}");
        }
    }

    #[test]
    fn intersecting_shoulder() {
        check(
            |r| random(r, [false; 3], true, false),
            |g, p, o| position_intersecting(g, p, &[0.0; 3], o),
        );
    }

    #[test]
    fn parallel_elbow() {
        check(
            |r| random(r, [false; 3], false, true),
            |g, p, o| position_parallel(g, p, &[0.0; 3], o),
        );
    }

    #[test]
    fn spherical_arm() {
        check(
            |r| random(r, [false, false, true], true, false),
            |g, p, o| position_intersecting_prismatic(g, p, &[0.0; 3], o),
        );
    }

    #[test]
    fn cylindrical_and_its_reverse() {
        for (first, prismatic) in [(true, [false, true, true]), (false, [true, true, false])] {
            check(
                |r| random(r, prismatic, false, false),
                |g, p, o| position_one_revolute(g, p, first, &[0.0; 3], o),
            );
        }
    }

    #[test]
    fn cartesian() {
        check(
            |r| random(r, [true; 3], false, false),
            |g, p, o| position_cartesian(g, p, &[0.0; 3], o),
        );
    }
}
