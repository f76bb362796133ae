//! **h2 ∥ h3 ∥ h4** with axes 5 and 6 not meeting (IK-Geo's "three parallel"; the UR
//! family, `ur.rs`, is the case h5 ∩ h6): rotations about the parallel axes keep the
//! component along them, which leaves two equations in (q1, q5) — SP6, a quartic. Then q6
//! and `θ = q2 ± q3 ± q4` from SP1, the elbow q3 from SP3 and q2 from SP1 in the plane ⟂
//! h2. Every branch is checked against `fk` (its fit is at least [`Fit::Checked`]); one
//! built on an ill-conditioned root is first polished on `fk` (`polish.rs`).

use super::WristPair;
use crate::ik::geometry::{flat, orthogonal, rot, Geometry, Pose};
use crate::ik::polish::polished;
use crate::ik::setup::target_point;
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{
    sp1, sp1_angle, sp1_from_sides, sp1_planar_sides, sp6, wrap, Fit, Plane, Sp3,
};

/// **h2 ∥ h3 ∥ h4, h5 and h6 not meeting**:
///
/// 1. `p16 = p0T − R06 p6T − p1` (`p6T` from joint 6's point)
/// 2. (q1, q5) — SP6: `h2ᵀ rot(−h1, q1) p16 − h2ᵀ rot(h5, q5) p56 = h2ᵀ (p12 + p23 + p34 + p45)`
///    and `h2ᵀ rot(−h1, q1) R06 h6 − h2ᵀ rot(h5, q5) h6 = 0`
/// 3. q6 — SP1: `rot(h6, q6) R06ᵀ R1 h2 = R5ᵀ h2`
/// 4. `θ = q2 ± q3 ± q4` — SP1: `rot(h2, θ) x = R1ᵀ R06 R6ᵀ R5ᵀ x` for an `x ⟂ h2`
/// 5. q3 — SP3, q2 — SP1 on `d = R1ᵀ p16 − p12 − rot(h2, θ) (p45 + R5 p56)` in the plane
///    ⟂ h2; q4 from θ.
///
/// At the wrist singularity (`R5ᵀ h2 ∥ h6`) q6 is free and θ follows from it.
pub fn three_parallel(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    _pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let [h1, h2, h3, h4, h5, h6] = g.h;
    let (s3, s4) = (h3.dot(&h2).signum(), h4.dot(&h2).signum());
    let (r06, c6) = target_point(g, pose, &g.p[5]);
    let p = g.p;
    let (p12, p23, p34, p45, p56) = (
        p[1] - p[0],
        p[2] - p[1],
        p[3] - p[2],
        p[4] - p[3],
        p[5] - p[4],
    );
    let p16 = c6 - p[0];
    let r06_h6 = r06 * h6;
    // hᵀ rot(−h1, q1) x = xᵀ rot(h1, q1) h: SP6's terms with h and x exchanged.
    let pairs = sp6(
        [p16, -h2, r06_h6, -h2],
        [h1, h5, h1, h5],
        [h2, p56, h2, h6],
        [h2.dot(&(p12 + p23 + p34 + p45)), 0.0],
    );
    let elbow = Sp3::new(&flat(&h2, &p34), &flat(&h2, &(-p23)), &h3);
    let plane = Plane::new(&h2);
    let (p23_, p34_) = (plane.split(&p23), plane.split(&p34));
    let x = orthogonal(&h2);
    for ((q1, q5), fit) in pairs.iter() {
        let (r1, r5) = (q1.rot(&h1), q5.rot(&h5));
        let r5_h2 = r5.tr_mul(&h2);
        // On a double root of (q1, q5) — at the wrist singularity, where it clusters — q5
        // is good to ~1e-8 only: R5ᵀ h2 within that of h6 is the singularity itself, q6
        // free (SP1 would read an angle off the rounding).
        let (q6, f6) = if fit >= Fit::Double && r5_h2.cross(&h6).norm() <= AT_THE_WRIST {
            (free[5], Fit::Free)
        } else {
            sp1(&r06.tr_mul(&(r1 * h2)), &r5_h2, &h6, free[5])
        };
        // R234 = R1ᵀ R06 R6ᵀ R5ᵀ, a rotation about h2 by θ.
        let r234 = r1.tr_mul(&r06) * rot(&h6, q6).transpose() * r5.transpose();
        let (t, ft) = sp1_angle(&x, &(r234 * x), &h2, 0.0);
        let reach = plane.split(&(r1.tr_mul(&p16) - p12 - t.rot(&h2) * (p45 + r5 * p56)));
        let t3 = elbow.solve(reach.flat_norm(), free[2]);
        for q3 in t3.as_slice() {
            let sides = sp1_planar_sides(&(p23_ + p34_.turn(q3, s3)), &reach);
            let (q2, f2) = sp1_from_sides(sides, free[1]);
            let q4 = wrap(s4 * (t.theta - q2 - s3 * q3.theta));
            let fit = fit.and(Fit::Checked).and(f6).and(ft).and(t3.fit).and(f2);
            let q = [q1.theta, q2, q3.theta, q4, q5.theta, q6];
            out.push(polished(g, q, pose, fit), fit);
        }
    }
}

/// `|R5ᵀ h2 × h6|` within which a double root of (q1, q5) is taken to be at the wrist
/// singularity: far above the ~1e-8 to which such a root is placed, far below any regular
/// wrist.
const AT_THE_WRIST: f64 = 1e-6;
