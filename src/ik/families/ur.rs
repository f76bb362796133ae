//! The UR family — **h2 ∥ h3 ∥ h4, h5 ∩ h6** (IK-Geo's "three parallel, two
//! intersecting"): Universal Robots UR3, UR5, UR10 and their e-series. q1 and q5 from SP4,
//! `θ = q2 ± q3 ± q4` from SP1, the elbow q3 from SP3 and q2 from SP1 in the plane ⟂ h2,
//! q6 from SP1. Regular poses of an orthogonal wrist take the lanes of
//! [`regular::three_parallel_two_intersecting`] first.

use super::{regular_first, Solvers, WristPair};
use crate::ik::geometry::{flat, mv, rot, Angle, Geometry, Pose, M3, V3};
#[cfg(not(feature = "small-ik"))]
use crate::ik::polish::{polish, pose_miss};
use crate::ik::regular;
use crate::ik::setup::ThreeParallel;
use crate::ik::solutions::Candidates;
#[cfg(not(feature = "small-ik"))]
use crate::ik::subproblems::Roots;
use crate::ik::subproblems::{
    half_turn, sp1, sp1_angle, sp1_angles_2, sp1_from_sides, sp1_planar_sides, sp3, sp4, wrap, Fit,
    Plane, Sp3, Sp4,
};
use core::f64::consts::PI;

/// **h2 ∥ h3 ∥ h4, h5 ∩ h6** (Universal Robots):
///
/// 1. `p16 = p0T − R06 p6T − p1` (`p6T` from where axes 5 and 6 meet)
/// 2. q1 — SP4: `h2ᵀ rot(−h1, q1) p16 = h2ᵀ (p12 + p23 + p34 + p45)`
/// 3. q5 — SP4: `h2ᵀ rot(h5, q5) h6 = h2ᵀ R1ᵀ R06 h6`
/// 4. `θ = q2 ± q3 ± q4` — SP1: `rot(h2, θ) R5 h6 = R1ᵀ R06 h6`
/// 5. q3 — SP3, q2 — SP1 on `d = R1ᵀ p16 − p12 − rot(h2, θ) p45`; q4 from θ
/// 6. q6 — SP1: `rot(h6, q6) h5 = (R1 R2 R3 R4 R5)ᵀ R06 h5`.
///
/// With [`WristPair::HalfTurn`] (`h2 ⟂ h5 ⟂ h6`) the second root of q5 takes
/// `(θ + π, q6 + π)` from the first instead of steps 4 and 6.
///
/// At the wrist singularity (`R5 h6 ∥ h2`, so h6 ∥ h2 ∥ h3 ∥ h4) the orientation fixes
/// only `θ ± q6`; the position then fixes q2, q3 once q4 is chosen: q4 = `free`, q3 — SP3
/// and q2 — SP1 on the arm `p23 + R3 (p34 + R4 p45)`, q6 from the rotation.
pub fn three_parallel_two_intersecting(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let solvers: Solvers = (
        regular::three_parallel_two_intersecting,
        three_parallel_two_intersecting_by_branch,
    );
    regular_first(solvers, g, pose, free, pair, out);
}

/// [`three_parallel_two_intersecting`] one branch after another, for every pose (the
/// singular and unreachable ones too); the regular ones take the lanes of
/// [`regular::three_parallel_two_intersecting`] first.
pub fn three_parallel_two_intersecting_by_branch(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let set_up = ThreeParallel::new(g, pose);
    let ([h1, h2, h3, h4, h5, h6], [p12, p23, p34, p45]) = (set_up.h, set_up.links);
    let (s3, s4, r06, p16) = (set_up.s3, set_up.s4, set_up.r06, set_up.p16);
    let t1 = sp4(&h2, &p16, &(-h1), h2.dot(&(p12 + p23 + p34 + p45)), free[0]);
    // The circles cut once per branch: h2ᵀ rot(h5, q5) h6 (step 3), and the elbow's with
    // θ known (step 5, in the plane ⟂ h2).
    let wrist5 = Sp4::new(&h2, &h6, &h5);
    let (r06_h5, r06_h6) = (mv(&r06, &h5), mv(&r06, &h6));
    let elbow = Sp3::new(&flat(&h2, &p34), &flat(&h2, &(-p23)), &h3);
    // The arm's plane ⟂ h2: turns about h2 ∥ h3 ∥ h4 are 2-D rotations there.
    let plane = Plane::new(&h2);
    let (p23_, p34_, p45_) = (plane.split(&p23), plane.split(&p34), plane.split(&p45));
    for q1 in t1.as_slice() {
        let r1t = q1.rot(&h1).transpose();
        // R1ᵀ R06 h5, R1ᵀ R06 h6: all the wrist needs of the target's rotation.
        let (target_h5, target_h6) = (mv(&r1t, &r06_h5), mv(&r1t, &r06_h6));
        let arm = mv(&r1t, &p16) - p12;
        let arm_ = plane.split(&arm);
        let t5 = wrist5.solve(h2.dot(&target_h6), free[4]);
        // Two roots of q5 merged into one (see `split_wrist`), for a second pass where
        // its branches miss the pose. (Not in the size-first build, `small-ik`: 1.6 KB of
        // flash on a Cortex-M4F, past its budget; there such a wrist keeps its merged,
        // least-squares branches.)
        #[cfg(not(feature = "small-ik"))]
        let (split, start, mut merged, mut t5) = (
            if t5.n == 1 && matches!(t5.fit, Fit::Double | Fit::LeastSquares) {
                wrist5.split(h2.dot(&target_h6))
            } else {
                None
            },
            out.as_slice().len(),
            None::<(Candidates<6, 8>, f64)>,
            t5,
        );
        // One pass, and a second on the split roots where the first was a merged one.
        #[cfg_attr(feature = "small-ik", allow(clippy::never_loop))]
        loop {
            // WristPair::HalfTurn: the first root's θ, its fit and q6, for the second root.
            let mut turned: Option<(Angle, Fit, (f64, Fit))> = None;
            for (k, q5) in t5.as_slice().iter().enumerate() {
                // q6 — SP1: R6 h5 = (R14 R5)ᵀ R1ᵀ R06 h5 with R14 = rot(h2, θ): with θ known,
                // one per (q1, q5), whichever elbow.
                let q6_for = |r5: &M3, r14: &M3| {
                    let x = mv(&r5.transpose(), &mv(&r14.transpose(), &target_h5));
                    sp1(&h5, &x, &h6, free[5])
                };
                let (mode, ft) = match (k, turned) {
                    // (θ + π, the other q5, q6 + π) solves the wrist like (θ, q5, q6).
                    (1, Some((t, ft, (q6, f6)))) => {
                        let q6 = (wrap(q6 + PI), f6);
                        (
                            Arm::Theta {
                                t: half_turn(t),
                                q6,
                            },
                            ft,
                        )
                    }
                    _ => {
                        let r5 = q5.rot(&h5);
                        // θ known, and with it q6.
                        let theta_known = |t: Angle| Arm::Theta {
                            t,
                            q6: q6_for(&r5, &t.rot(&h2)),
                        };
                        let (theta, ft) = sp1_angle(&mv(&r5, &h6), &target_h6, &h2, 0.0);
                        // The arm (q2, q3, q4): θ known (q4 from it), or at the wrist
                        // singularity q4 = free — or, when that q4 puts the wrist out of the
                        // elbow's reach, θ chosen mid-range of what the elbow can reach,
                        // nearest to free's.
                        let mode = if ft == Fit::Free {
                            let q4 = free[3];
                            let known = p34 + mv(&rot(&h4, q4), &p45);
                            let t = sp3(
                                &flat(&h2, &known),
                                &flat(&h2, &(-p23)),
                                &h3,
                                flat(&h2, &arm).norm(),
                                0.0,
                            );
                            if t.fit == Fit::LeastSquares {
                                let hint = free[1] + s3 * free[2] + s4 * free[3];
                                let theta = mid_range_theta(&h2, &arm, &p23, &p34, &p45, hint);
                                theta_known(Angle::new(theta))
                            } else {
                                Arm::Q4 { q4, known, r5 }
                            }
                        } else {
                            theta_known(theta)
                        };
                        (mode, ft)
                    }
                };
                let fit = t1.fit.and(t5.fit).and(ft);
                if let (0, WristPair::HalfTurn, Arm::Theta { t, q6 }) = (k, pair, mode) {
                    // θ from the wrist (not the singular branch's choice).
                    if ft != Fit::Free {
                        turned = Some((t, ft, q6));
                    }
                }
                match mode {
                    Arm::Theta { t, q6: (q6, f6) } => {
                        // In the plane ⟂ h2 (the components along h2 agree by step 2): the
                        // wrist centre's offset `reach = arm − rot(h2, θ) p45` from joint 2,
                        // and per q3 the arm `p23 + R3 p34` that q2 turns onto it.
                        let reach = arm_ - p45_.turn(&t, 1.0);
                        let t3 = elbow.solve(reach.flat_norm(), free[2]);
                        // q2 — SP1 for each elbow (with two, their atan2 side by side).
                        let sides =
                            |q3: &Angle| sp1_planar_sides(&(p23_ + p34_.turn(q3, s3)), &reach);
                        let q2s = if t3.n == 2 {
                            sp1_angles_2([sides(&t3.angles[0]), sides(&t3.angles[1])], [free[1]; 2])
                        } else {
                            [sp1_from_sides(sides(&t3.angles[0]), free[1]); 2]
                        };
                        for (q3, (q2, f2)) in t3.as_slice().iter().zip(q2s) {
                            let q4 = wrap(s4 * (t.theta - q2 - s3 * q3.theta));
                            out.push(
                                [q1.theta, q2, q3.theta, q4, q5.theta, q6],
                                fit.and(t3.fit).and(f2).and(f6),
                            );
                        }
                    }
                    Arm::Q4 { q4, known, r5 } => {
                        // θ, so q6, depends on the elbow: found per q3.
                        let t3 = sp3(
                            &flat(&h2, &known),
                            &flat(&h2, &(-p23)),
                            &h3,
                            flat(&h2, &arm).norm(),
                            free[2],
                        );
                        for q3 in t3.as_slice() {
                            let (q2, f2) =
                                sp1(&(p23 + mv(&q3.rot(&h3), &known)), &arm, &h2, free[1]);
                            let (q6, f6) = q6_for(&r5, &rot(&h2, q2 + s3 * q3.theta + s4 * q4));
                            out.push(
                                [q1.theta, q2, q3.theta, q4, q5.theta, q6],
                                fit.and(t3.fit).and(f2).and(f6),
                            );
                        }
                    }
                }
            }
            #[cfg(not(feature = "small-ik"))]
            match (split, merged.take()) {
                (Some(roots), None) => {
                    if let Some(one) = split_wrist(g, pose, out, start) {
                        merged = Some(one);
                        t5 = Roots {
                            angles: roots,
                            n: 2,
                            fit: Fit::Double,
                        };
                        continue;
                    }
                }
                (Some(_), Some((one, miss))) => keep_closer(g, pose, out, start, &one, miss),
                _ => {}
            }
            break;
        }
    }
}

/// The least miss of `candidates` on the pose ([`pose_miss`]).
#[cfg(not(feature = "small-ik"))]
fn closest(g: &Geometry<6>, pose: &Pose, candidates: &Candidates<6, 8>) -> f64 {
    candidates
        .as_slice()
        .iter()
        .map(|c| pose_miss(g, pose, &c.q))
        .fold(f64::INFINITY, f64::min)
}

/// A q5 merged into a double root (two roots closer than SP4's merge distance, `2√1e-11
/// ≈ 6e-6` rad) whose branches — `out` from `start` — miss the pose by more than
/// [`ROUNDED_POSE`]: the two roots were both real, the wrist a few µrad from its
/// singularity and not at it, where q4 is not free (the merged branch, taking it so,
/// misses by about |q5|). Then the merged branches are taken out of `out` and returned
/// with their [`closest`] miss, for the caller to solve both roots in their place
/// ([`keep_closer`]); `None` where they come closer (the wrist at its singularity, to
/// rounding: q4 from `free` is the answer).
#[cfg(not(feature = "small-ik"))]
#[cold]
fn split_wrist(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
    start: usize,
) -> Option<(Candidates<6, 8>, f64)> {
    let mut one = Candidates::default();
    for c in &out.as_slice()[start..] {
        one.push(c.q, c.fit);
    }
    let merged_miss = closest(g, pose, &one);
    (merged_miss > ROUNDED_POSE).then(|| {
        out.truncate(start);
        (one, merged_miss)
    })
}

/// The split roots' branches (`out` from `start`) polished on `fk` — θ and q6 carry the
/// rounding amplified by the inverse of the distance to the singularity — and flagged
/// `Double` (`finish` checks them), each kept where it comes closer to the pose than the
/// merged branches `one`, whose closest misses by `merged_miss` (a root whose elbow
/// cannot reach the wrist centre stays far off); the merged branches again where none
/// does.
#[cfg(not(feature = "small-ik"))]
#[cold]
fn keep_closer(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
    start: usize,
    one: &Candidates<6, 8>,
    merged_miss: f64,
) {
    let two = *out;
    out.truncate(start);
    for c in &two.as_slice()[start..] {
        let q = polish(g, c.q, pose).map(wrap);
        if pose_miss(g, pose, &q) < merged_miss {
            out.push(q, c.fit.and(Fit::Double));
        }
    }
    if out.as_slice().len() == start {
        for c in one.as_slice() {
            out.push(c.q, c.fit);
        }
    }
}

/// How far (largest entry) the merged branches of a wrist may miss the pose and still
/// stand for it, q4 taken from `free` ([`split_wrist`]): a pose rounded to `f32` (the
/// f32 `ik` solves it in f64) leaves a wrist at its singularity ~1e-7 from it, and there
/// the merged branch — exact at the f32 tolerance — keeps `ik_near` continuous. A wrist
/// of an f64 pose this near its singularity keeps its merged branches too, least squares
/// (missing by less than this).
#[cfg(not(feature = "small-ik"))]
const ROUNDED_POSE: f64 = 1e-6;

/// What fixes the UR arm's last parallel joint.
#[derive(Clone, Copy)]
enum Arm {
    /// `θ = q2 ± q3 ± q4` is known, so is q6 (which does not depend on the elbow then).
    Theta { t: Angle, q6: (f64, Fit) },
    /// q4 is (the wrist singularity's free joint), so is the wrist centre's offset from
    /// joint 3, `known = p34 + rot(h4, q4) p45`; `r5 = rot(h5, q5)` for q6 per elbow.
    Q4 { q4: f64, known: V3, r5: M3 },
}

/// At the UR wrist singularity: the `θ` nearest to `hint` that puts the wrist centre in
/// the middle of the elbow's reach (`‖p23⊥ + R3 p34⊥‖` ranges over `[|a − b|, a + b]`
/// across the plane ⟂ h2; the middle, `max(a, b)`, is reachable whatever the pose).
fn mid_range_theta(h2: &V3, arm: &V3, p23: &V3, p34: &V3, p45: &V3, hint: f64) -> f64 {
    let r = flat(h2, p23).norm().max(flat(h2, p34).norm());
    let roots = sp3(&flat(h2, p45), &flat(h2, arm), h2, r, hint);
    let gap = |t: f64| wrap(t - hint).abs();
    let mut best = roots.angles[0].theta;
    for t in roots.thetas() {
        if gap(t) < gap(best) {
            best = t;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::super::tests::solved;
    use super::*;
    use crate::ik::geometry::examples::ur5;
    use crate::ik::subproblems::Fit;

    #[test]
    fn ur5_all_eight_and_the_generating_one() {
        let g = ur5();
        let q = [0.3, -1.1, 1.4, -0.6, 0.9, 2.0];
        let pose = g.fk(&q);
        let solve = solved(
            three_parallel_two_intersecting,
            &g,
            &pose,
            &[0.0; 6],
            WristPair::Solve,
        );
        // The UR5's wrist is orthogonal (h2 ⟂ h5 ⟂ h6): the half-turn shortcut
        // gives the same eight solutions, in the same order.
        let turned = solved(
            three_parallel_two_intersecting,
            &g,
            &pose,
            &[0.0; 6],
            WristPair::HalfTurn,
        );
        for sols in [solve, turned] {
            assert_eq!(sols.as_slice().len(), 8);
            for c in sols.as_slice() {
                assert_eq!(c.fit, Fit::Exact);
                let t = g.fk(&c.q);
                assert!(
                    (t.p - pose.p).norm() < 1e-12 && (t.r - pose.r).norm() < 1e-12,
                    "{:?}",
                    c.q
                );
            }
            assert!(sols
                .as_slice()
                .iter()
                .any(|c| (0..6).all(|i| wrap(c.q[i] - q[i]).abs() < 1e-9)));
        }
        for (a, b) in solve.as_slice().iter().zip(turned.as_slice()) {
            assert!(
                (0..6).all(|i| wrap(a.q[i] - b.q[i]).abs() < 1e-12),
                "{a:?} {b:?}"
            );
        }
    }

    /// A wrist a few µrad from its singularity (q5 closer to 0 than SP4's merge distance,
    /// `2√1e-11` rad, lets the two roots ±q5 merge): not singular, so q4 is not free — the
    /// merged branch misses the pose by about |q5| (it gave only least-squares branches,
    /// 2.8e-6 off, and `ik_near` jumped to another shoulder). The two roots are solved
    /// instead and polished; the generating configuration is among them, reaching the pose.
    /// (The size-first build keeps the merged branches: see the solver.)
    #[test]
    #[cfg(not(feature = "small-ik"))]
    fn a_wrist_microradians_from_its_singularity_is_split() {
        use crate::ik::solutions::EXACT_TOLERANCE;
        let g = ur5();
        // (|q5| ≥ 1.5e-6: a wrist nearer to its singularity keeps its merged branches,
        // see `ROUNDED_POSE`.)
        for (q5, q3) in [(2.8e-6, 0.5), (-2e-6, 1.4), (3.1e-6, 0.0), (1.5e-6, -0.7)] {
            let q = [-1.1, 0.3, q3, -0.6, q5, 2.0];
            let pose = g.fk(&q);
            let sols = solved(
                three_parallel_two_intersecting,
                &g,
                &pose,
                &[0.0; 6],
                WristPair::HalfTurn,
            );
            let hit = sols
                .as_slice()
                .iter()
                // (Found to ~1e-16 / |q5| rad: the wrist's conditioning.)
                .find(|c| (0..6).all(|i| wrap(c.q[i] - q[i]).abs() < 1e-7))
                .unwrap_or_else(|| panic!("{q:?} not among {:?}", sols.as_slice()));
            let t = g.fk(&hit.q);
            let miss = (t.p - pose.p).amax().max((t.r - pose.r).amax());
            assert!(miss <= EXACT_TOLERANCE, "{hit:?} misses by {miss:e}");
            assert!(
                hit.fit >= Fit::Double,
                "{hit:?}: near a singularity, checked"
            );
        }
    }

    #[test]
    fn ur5_wrist_singularity_takes_q4_from_free() {
        let g = ur5();
        let q = [0.3, -1.1, 1.4, -0.6, 0.0, 2.0];
        let pose = g.fk(&q);
        let sols = solved(
            three_parallel_two_intersecting,
            &g,
            &pose,
            &q,
            WristPair::Solve,
        );
        let hit = sols
            .as_slice()
            .iter()
            .find(|c| (0..6).all(|i| wrap(c.q[i] - q[i]).abs() < 1e-9))
            .expect("the generating configuration");
        assert_eq!(hit.fit, Fit::Free);
        // Any other value of the free joint is a solution too.
        for free in [q, [0.0; 6]] {
            let sols = solved(
                three_parallel_two_intersecting,
                &g,
                &pose,
                &free,
                WristPair::Solve,
            );
            assert!(!sols.as_slice().is_empty());
            for c in sols.as_slice() {
                let t = g.fk(&c.q);
                assert!(
                    (t.p - pose.p).norm() < 1e-12 && (t.r - pose.r).norm() < 1e-12,
                    "{c:?}"
                );
            }
        }
    }
}
