//! The PUMA family — a **spherical wrist** (h4, h5, h6 meet in one point) **and h2 ∥ h3**
//! (h1 ∦ h2): the PUMA 560, KUKA KR, ABB IRB 120/140. q1 from SP4, the elbow q3 from SP3
//! and q2 from SP1 in the plane ⟂ h2, then the wrist (`wrist.rs`). Regular poses of an
//! orthogonal wrist take the lanes of [`regular::spherical_two_parallel`] first.

use super::wrist::{with_wrist, Wrist};
use super::{regular_first, Solvers, WristPair};
use crate::ik::geometry::{flat, Angle, Geometry, Pose};
use crate::ik::regular;
use crate::ik::setup::WristArm;
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp1_planar_angle, sp4, Plane, Sp3};

/// **Spherical wrist, h2 ∥ h3** (PUMA 560, KUKA KR, ABB IRB 120/140):
///
/// 1. wrist centre `w = p0T − R06 p6T`; `p16 = w − p1`
/// 2. q1 — SP4: `h2ᵀ rot(−h1, q1) p16 = h2ᵀ (p12 + p23 + p34)` (rotations about
///    h2 ∥ h3 keep the h2 component)
/// 3. q3 — SP3: `‖p23 + rot(h3, q3) p34‖ = ‖rot(−h1, q1) p16 − p12‖`
/// 4. q2 — SP1: `rot(h2, q2) (p23 + R3 p34) = rot(−h1, q1) p16 − p12`
/// 5. q5 — SP4, q4 and q6 — SP1 on `R36 = (R1 R2 R3)ᵀ R06` (the second root of q5 from
///    the first with [`WristPair::HalfTurn`]).
pub fn spherical_two_parallel(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let solvers: Solvers = (
        regular::spherical_two_parallel,
        spherical_two_parallel_by_branch,
    );
    regular_first(solvers, g, pose, free, pair, out);
}

/// [`spherical_two_parallel`] one branch after another, for every pose (the singular and
/// unreachable ones too); the regular ones take the lanes of
/// [`regular::spherical_two_parallel`] first.
pub fn spherical_two_parallel_by_branch(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let wrist = Wrist::new(g, pair);
    let WristArm {
        r06,
        links: [p12, p23, p34],
        p16,
    } = WristArm::new(g, pose);
    let [h1, h2, h3, ..] = g.h;
    let t1 = sp4(&h2, &p16, &(-h1), h2.dot(&(p12 + p23 + p34)), free[0]);
    // In the plane ⟂ h2 (the components along it agree by step 2): no axial offsets
    // in the distances, whose rounding would blur the elbow's double root.
    let elbow = Sp3::new(&flat(&h3, &p34), &flat(&h3, &(-p23)), &h3);
    // h3 = σ h2 (the engine proved them parallel): R2 R3 = rot(h2, q2 + σ q3), a 2-D
    // rotation in the plane ⟂ h2.
    let s3 = h3.dot(&h2).signum();
    let plane = Plane::new(&h2);
    let (p23_, p34_) = (plane.split(&p23), plane.split(&p34));
    // The wrist needs R36 h6 = R23ᵀ (R1ᵀ R06 h6) and R36ᵀ h4 = (R06ᵀ R1) (R23 h4).
    let (h4, h6) = (wrist.h[0], wrist.h[2]);
    let (r06_h6, h4_) = (r06 * h6, plane.split(&h4));
    for q1 in t1.as_slice() {
        // R1 = rot(h1, q1); rot(−h1, q1) = R1ᵀ.
        let r1 = q1.rot(&h1);
        let v = plane.split(&(r1.tr_mul(&p16) - p12));
        let r1t_r06_h6 = plane.split(&r1.tr_mul(&r06_h6));
        let t3 = elbow.solve(v.flat_norm(), free[2]);
        for q3 in t3.as_slice() {
            let (q2, f2) = sp1_planar_angle(&(p23_ + p34_.turn(q3, s3)), &v, free[1]);
            let fit = t1.fit.and(t3.fit).and(f2);
            let q23 = Angle {
                theta: q2.theta + s3 * q3.theta,
                sin: q2.sin * q3.cos + s3 * q2.cos * q3.sin,
                cos: q2.cos * q3.cos - s3 * q2.sin * q3.sin,
            };
            let target = (
                plane.join(&r1t_r06_h6.turn(&q23, -1.0)),
                r06.tr_mul(&(r1 * plane.join(&h4_.turn(&q23, 1.0)))),
            );
            let r36 = || (r1 * q23.rot(&h2)).tr_mul(&r06);
            let q123 = [q1.theta, q2.theta, q3.theta];
            with_wrist((g, pose), &wrist, q123, (target, r36), fit, free, out);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::solved;
    use super::*;
    use crate::ik::geometry::examples::puma;
    use crate::ik::subproblems::{wrap, Fit};

    #[test]
    fn orthogonal_spherical_wrist_half_turns() {
        let g = puma();
        let q = [0.4, -0.7, 0.9, 1.2, -0.8, 0.3];
        let pose = g.fk(&q);
        let solve = solved(
            spherical_two_parallel,
            &g,
            &pose,
            &[0.0; 6],
            WristPair::Solve,
        );
        let turned = solved(
            spherical_two_parallel,
            &g,
            &pose,
            &[0.0; 6],
            WristPair::HalfTurn,
        );
        assert_eq!(solve.as_slice().len(), 8);
        assert_eq!(turned.as_slice().len(), 8);
        for (a, b) in solve.as_slice().iter().zip(turned.as_slice()) {
            assert_eq!((a.fit, b.fit), (Fit::Exact, Fit::Exact));
            assert!(
                (0..6).all(|i| wrap(a.q[i] - b.q[i]).abs() < 1e-12),
                "{a:?} {b:?}"
            );
            let t = g.fk(&b.q);
            assert!((t.p - pose.p).norm() < 1e-12 && (t.r - pose.r).norm() < 1e-12);
        }
    }
}
