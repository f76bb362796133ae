//! A **spherical wrist** (h4, h5, h6 meet in one point) on an arm whose first three axes
//! are in no special position — neither h1 ∩ h2 nor h2 ∥ h3 (IK-Geo's "spherical"): the
//! wrist centre from (q1, q2, q3) is SP5, a quartic, then the wrist (`wrist.rs`). Every
//! branch is checked against `fk` (its fit is at least [`Fit::Checked`]); one built on an
//! ill-conditioned root is first polished on `fk` (`polish.rs`).

use super::wrist::{with_wrist, Wrist};
use super::WristPair;
use crate::ik::geometry::{Geometry, Pose};
use crate::ik::polish::polished;
use crate::ik::setup::WristArm;
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp5, Fit};

/// **Spherical wrist, general arm**:
///
/// 1. wrist centre `w = p0T − R06 p6T`; `p16 = w − p1`
/// 2. (q1, q2, q3) — SP5: `−p12 + rot(−h1, q1) p16 = rot(h2, q2) (p23 + rot(h3, q3) p34)`
///    (`p34` to the wrist centre): SP6 in (q1, q3) on the component along h2 and the
///    length, a quartic; q2 by SP1
/// 3. the wrist as in [`spherical_two_parallel`](fn@super::spherical_two_parallel)
///    (step 5).
pub fn spherical(
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
    // rot(−h1, q1) = R1ᵀ: SP5's θ1 is q1.
    let arm = sp5(&(-p12), &(-h1), &p16, &h2, &p23, &h3, &p34, free[1]);
    for ([q1, q2, q3], fit) in arm.iter() {
        let r36 = (q1.rot(&h1) * q2.rot(&h2) * q3.rot(&h3)).transpose() * r06;
        let q123 = [q1.theta, q2.theta, q3.theta];
        let wrist_of = (wrist.target(&r36), || r36);
        with_wrist(
            (g, pose),
            &wrist,
            q123,
            wrist_of,
            fit.and(Fit::Checked),
            free,
            out,
        );
    }
    for c in out.as_mut_slice() {
        c.q = polished(g, c.q, pose, c.fit);
    }
}
