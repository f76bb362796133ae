//! **Spherical wrist, h1 ∩ h2** with an orthogonal wrist, for a regular pose: the steps of
//! `families::spherical_two_intersecting` level by level — the elbow's two roots (q3),
//! the two meeting points of each elbow's SP2 (q1, q2), then the four wrists' q5 (first
//! root), q4 and q6 (the second root by half turns). The Franka Panda (joint 7 locked)
//! is this family read from the tool; the KUKA iiwa with joint 3 locked is it as written.

use super::{direction, push_wrist_pair, rotate, sides, wrist, WristLanes, FAR};
use crate::ik::geometry::{meet, Geometry, Pose, V3};
use crate::ik::lanes::{Lanes, Vectors};
use crate::ik::setup::wrist_centre;
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{roots_of, Fit, Sp2Lanes, Sp3Lanes};
use crate::math::fast_atan2_n;

/// **Spherical wrist, h1 ∩ h2** (`WristPair::HalfTurn`), for a regular pose. The
/// candidates go to `out` (empty before, and left untouched unless the pose is regular),
/// but for the branches whose shoulder misses a pose another branch reaches by more than
/// `FAR` (see the module doc of [`regular`](super)); `None` where a level is not regular
/// in some lane, or the elbow cannot reach the wrist centre (every branch least squares:
/// the branch-by-branch solve gives their nearest). The caller keeps shoulders whose axes
/// are nearly parallel from it (the family's solve polishes those).
pub fn spherical_two_intersecting(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    best_build!(spherical_two_intersecting_lanes(g, pose, out))
}

/// [`spherical_two_intersecting`] itself, inlined into each of its builds.
#[inline(always)]
pub(super) fn spherical_two_intersecting_lanes(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    let [h1, h2, h3, h4, h5, h6] = g.h;
    // 1. The wrist centre w, seen from c12, where axes 1 and 2 meet.
    let (r06, w0, w) = wrist_centre(g, pose);
    let c12 = meet(g, 0, 1);
    let (p23, p3w, d) = (g.p[2] - c12, w0 - g.p[2], w - c12);
    // 2. q3 — SP3: ‖p23 + rot(h3, q3) p3w‖ = ‖d‖.
    let elbow = Sp3Lanes::new(&p3w, &(-p23), &h3);
    let q3 = elbow.solve(Lanes([d.norm_squared()]))?;
    if !q3.exact[0] {
        return None;
    }
    let (c3, s3): (Lanes<2>, Lanes<2>) = (
        Lanes([q3.cos[0].0[0], q3.cos[1].0[0]]),
        Lanes([q3.sin[0].0[0], q3.sin[1].0[0]]),
    );
    // 3. (q1, q2) — SP2: rot(−h1, q1) d = rot(h2, q2) (p23 + R3 p3w), then SP1 from each
    // meeting point z. Four branches (q3, z) from here on; a shoulder whose circles miss
    // has one least-squares point.
    let arm = rotate(&h3, &Vectors::splat(&p3w), (c3, s3)) + Vectors::splat(&p23);
    let shoulder = Sp2Lanes::<2, 4>::solve(&d, &arm, &(-h1), &h2)?;
    // (The SP1s' own fits are not used: a least-squares meeting point lies off both
    // circles, which SP2's fit says already — as in `sp2`.)
    let (q1_y, q1_x, _) = sides(&Vectors::splat(&d), &shoulder.z, &(-h1))?;
    let arm4 = arm.twice::<4>();
    let (q2_y, q2_x, _) = sides(&arm4, &shoulder.z, &h2)?;
    let ((c1, s1), (c2, s2)) = (direction(q1_y, q1_x), direction(q2_y, q2_x));
    let (c3, s3) = (c3.twice::<4>(), s3.twice::<4>());
    // 4. The wrist: R36 h6 = R3ᵀ R2ᵀ R1ᵀ R06 h6 and R36ᵀ h4 = R06ᵀ R1 R2 R3 h4, with
    // R1 = rot(h1, q1) (q1 turns d about −h1: R1ᵀ d = z).
    let r1t_h6 = rotate(&h1, &Vectors::splat(&(r06 * h6)), (c1, -s1));
    let r36_h6 = rotate(&h3, &rotate(&h2, &r1t_h6, (c2, -s2)), (c3, -s3));
    let r3_h4 = rotate(&h3, &Vectors::splat(&h4), (c3, s3));
    let r36t_h4 = rotate(&h1, &rotate(&h2, &r3_h4, (c2, s2)), (c1, s1)).tr_mul_by(&r06);
    // q5, q4, q6, all in the base frame.
    let WristLanes {
        circle: wrist5,
        q5,
        q4: (q4_y, q4_x, q4_exact),
        q6: (q6_y, q6_x, q6_exact),
    } = wrist([h4, h5, h6], |v| *v, &r36_h6, &r36t_h4)?;
    let exact = |j: usize| shoulder.exact[j / 2] && q4_exact[j] && q6_exact[j];
    // A shoulder that misses has one branch, j = 2 i; its orientation is exact where its
    // q4 and q6 are, and its position misses by |R1ᵀ d − R2 arm|.
    let misses: [bool; 4] = core::array::from_fn(|j| {
        j % 2 == 0 && !shoulder.exact[j / 2] && q4_exact[j] && q6_exact[j]
    });
    let far = if misses.contains(&true) && (out.wants_reaching_only() || (0..4).any(exact)) {
        far_shoulders(&d, &arm4, (&h1, &h2), [(c1, s1), (c2, s2)], misses)
    } else {
        [false; 4]
    };
    // Every angle in one pass: q1 (4), q2 (4), q5's d (4), q4 (4), q6 (4), q3's d, and
    // the angles φ of the two circles cut.
    let mut ys = [0.0; 23];
    let mut xs = [0.0; 23];
    for (at, (y, x)) in [
        (0, (q1_y, q1_x)),
        (4, (q2_y, q2_x)),
        (8, (q5.y, q5.x)),
        (12, (q4_y, q4_x)),
        (16, (q6_y, q6_x)),
    ] {
        ys[at..at + 4].copy_from_slice(&y.0);
        xs[at..at + 4].copy_from_slice(&x.0);
    }
    (ys[20], xs[20]) = (q3.y.0[0], q3.x.0[0]);
    (ys[21], xs[21]) = elbow.phi_sides();
    (ys[22], xs[22]) = wrist5.phi_sides();
    let t = fast_atan2_n(ys, xs);
    for (i, q3) in roots_of(t[21], t[20]).into_iter().enumerate() {
        let points = if shoulder.exact[i] { 2 } else { 1 };
        for j in (2 * i..).take(points) {
            if far[j] {
                continue;
            }
            let q5 = roots_of(t[22], t[8 + j]);
            let fit = if exact(j) {
                Fit::Exact
            } else {
                Fit::LeastSquares
            };
            push_wrist_pair(out, [t[j], t[4 + j], q3], (t[12 + j], q5, t[16 + j]), fit);
        }
    }
    Some(())
}

/// Of the `misses` lanes — a shoulder whose circles miss, the orientation exact — those
/// whose position misses by more than [`FAR`]: `|R1ᵀ d − R2 arm|`, the wrist centre's
/// miss (and the tool's: the orientation is the pose's). Inlined into the solver's
/// build (AVX2 where it has it): the Panda has such a lane at about 60 % of its poses.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn far_shoulders(
    d: &V3,
    arm: &Vectors<4>,
    (h1, h2): (&V3, &V3),
    [(c1, s1), (c2, s2)]: [(Lanes<4>, Lanes<4>); 2],
    misses: [bool; 4],
) -> [bool; 4] {
    let gap = rotate(h1, &Vectors::splat(d), (c1, -s1)) - rotate(h2, arm, (c2, s2));
    let miss = gap.dot(&gap).sqrt();
    core::array::from_fn(|j| misses[j] && miss.0[j] > FAR)
}
