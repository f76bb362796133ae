//! A **spherical wrist** (h4, h5, h6 meet in one point) **and h1 ∩ h2** (the shoulder's
//! axes meet): with joint 3 revolute, a KUKA iiwa with its joint 3 locked; with joint 3
//! prismatic, the Stanford arm. The elbow from SP3 (prismatic: a quadratic in q3), (q1, q2)
//! from SP2, then the wrist (`wrist.rs`). Where a 7-joint arm's locked joint lines the
//! shoulder's axes up, the parallel-shoulder decomposition instead. Regular poses of an
//! orthogonal wrist, the shoulder's axes well apart, take the lanes of
//! [`regular::spherical_two_intersecting`] first.

use super::position::{shoulder_elbow, shoulder_slide};
use super::wrist::{with_wrist, Wrist};
use super::{regular_first, Solvers, WristPair};
use crate::ik::continuum::slid_to_free;
use crate::ik::double_root::merge_double_roots;
use crate::ik::geometry::{flat, meet, rot, Geometry, Pose, M3, V3};
use crate::ik::polish::{polish, polished_keeping};
use crate::ik::regular;
use crate::ik::setup::wrist_centre;
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp1, sp3, sp4, Fit};

/// **Spherical wrist, h1 ∩ h2** (the shoulder axes meet):
///
/// 1. `p16 = w − c12`, `c12` where axes 1 and 2 meet
/// 2. q3 — SP3: `‖p23 + rot(h3, q3) p34‖ = ‖p16‖`
/// 3. (q1, q2) — SP2: `rot(−h1, q1) p16 = rot(h2, q2) (p23 + R3 p34)`
/// 4. wrist as in [`spherical_two_parallel`](fn@super::spherical_two_parallel) (step 5).
pub fn spherical_two_intersecting(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    // Nearly parallel shoulder axes need the checks and the polish below.
    if g.h[0].cross(&g.h[1]).norm_squared() <= SHOULDER_GRAZING {
        spherical_two_intersecting_by_branch(g, pose, free, pair, out);
        return;
    }
    let solvers: Solvers = (
        regular::spherical_two_intersecting,
        spherical_two_intersecting_by_branch,
    );
    regular_first(solvers, g, pose, free, pair, out);
}

/// [`spherical_two_intersecting`] one branch after another, for every pose (the singular
/// and unreachable ones too); the regular ones take the lanes of
/// [`regular::spherical_two_intersecting`] first.
pub fn spherical_two_intersecting_by_branch(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let wrist = Wrist::new(g, pair);
    let (r06, w0, w) = wrist_centre(g, pose);
    let [h1, h2, ..] = g.h;
    let skew = h1.cross(&h2).norm_squared();
    if skew <= SHOULDER_PARALLEL {
        parallel_shoulder(g, pose, &wrist, (r06, w0, w), free, out);
        return;
    }
    // Nearly parallel: the meeting point is far out (≳ 1e6 × the axes' offset), and the
    // distances through it lose digits. The branches are checked against `fk`.
    let far = if skew <= SHOULDER_FAR {
        Fit::Double
    } else if skew <= SHOULDER_GRAZING {
        Fit::Checked
    } else {
        Fit::Exact
    };
    let c12 = meet(g, 0, 1);
    shoulder_elbow(g, c12, w0, w, free, |q1, q2, q3, r3, fit| {
        let r36 = (q1.rot(&h1) * q2.rot(&h2) * r3).transpose() * r06;
        let q123 = [q1.theta, q2.theta, q3.theta];
        let wrist_of = (wrist.target(&r36), || r36);
        with_wrist((g, pose), &wrist, q123, wrist_of, fit.and(far), free, out);
    });
    if skew <= SHOULDER_GRAZING {
        polish_all(g, pose, free, out);
    } else {
        polish_singular(g, pose, free, out);
    }
}

/// The singular candidates ([`Fit::Double`], [`Fit::Free`]) brought onto `pose` on `fk`,
/// a continuum's free joints kept at the caller's values ([`polished_keeping`]): at a
/// straight elbow the wrist centre is on the shoulder's second axis, SP2's circles touch,
/// and the double root's rounding, amplified by its square root, left the iiwa with
/// joint 2 locked at 0.109 (its shoulder 0.109 rad from parallel, past
/// [`SHOULDER_GRAZING`]) 1.4e-7 off a pose it reaches.
#[cold]
#[inline(never)]
fn polish_singular(g: &Geometry<6>, pose: &Pose, free: &[f64; 6], out: &mut Candidates<6, 8>) {
    let mut singular = false;
    for c in out.as_mut_slice() {
        if matches!(c.fit, Fit::Double | Fit::Free) {
            c.q = polished_keeping(g, c.q, pose, c.fit, free);
            singular = true;
        }
    }
    if singular {
        on_continua(g, pose, free, out);
    }
}

/// Every candidate brought onto `pose` on `fk`, a continuum's free joints kept at the
/// caller's values ([`polished_keeping`]) (out of line: a grazing shoulder is rare, and
/// the regular path keeps its code as it was).
#[cold]
#[inline(never)]
fn polish_all(g: &Geometry<6>, pose: &Pose, free: &[f64; 6], out: &mut Candidates<6, 8>) {
    for c in out.as_mut_slice() {
        c.q = match c.fit {
            Fit::Free => polished_keeping(g, c.q, pose, c.fit, free),
            _ => polish(g, c.q, pose),
        };
    }
    on_continua(g, pose, free, out);
}

/// Polished branches made what the subproblems give where they see a singularity: the
/// two halves of a double root that rounding split (within
/// [`DOUBLE_ROOT`](crate::ik::double_root::DOUBLE_ROOT)) one branch
/// flagged [`Fit::Double`] ([`merge_double_roots`]), and a branch on a continuum of
/// solutions its point at the caller's values ([`slid_to_free`]).
fn on_continua(g: &Geometry<6>, pose: &Pose, free: &[f64; 6], out: &mut Candidates<6, 8>) {
    merge_double_roots(g, pose, out);
    for c in out.as_mut_slice() {
        c.q = slid_to_free(g, c.q, pose, free);
    }
}

/// `|h1 × h2|²` at or below which the shoulder's axes are taken as parallel: the engine
/// proved they meet for every value of a 7-joint arm's locked joint, but at particular
/// values they line up (the iiwa with joint 2 locked at q2 = 0: axes 1 and 3 coincide
/// in the DH table, and are parallel 0.436 mm apart in ROS-Industrial's URDF).
const SHOULDER_PARALLEL: f64 = 1e-24;

/// `|h1 × h2|²` below which the meeting point is so far out that the branches through it
/// are checked against `fk` (flagged [`Fit::Double`]) rather than trusted.
const SHOULDER_FAR: f64 = 1e-12;

/// `|h1 × h2|²` (the shoulder's axes within about 0.1 rad of parallel) below which SP2's
/// circles meet at a grazing angle δ and its roots carry rounding amplified by about
/// 1/δ²: measured on the iiwa with joint 2 locked near 0, 1e-13/δ² of the pose (7.7e-9 at
/// δ = 2.2e-3, 1e-11 at δ = 0.04–0.09). Every branch is then brought onto the pose by
/// Gauss–Newton on `fk` (`polish.rs`) and checked there ([`Fit::Checked`]).
const SHOULDER_GRAZING: f64 = 1e-2;

/// The spherical-wrist family with the shoulder's axes parallel at this pose (`h2 = σ h1`,
/// possibly one line), so `R1 R2 = rot(h1, q1 + σ q2)`:
///
/// 1. q3 — SP4: `h1ᵀ rot(h3, q3) p34 = h1ᵀ (p16 − p12 − p23)` (turns about h1 keep it)
/// 2. q2 — SP3 in the plane ⟂ h1: `‖p12⊥ + rot(h2, q2) v⊥‖ = ‖p16⊥‖`, `v = p23 + R3 p34`
///    (free when the axes are one line: `p12⊥ = 0`)
/// 3. q1 — SP1: `rot(h1, q1) (p12 + R2 v) = p16`; the wrist as above.
fn parallel_shoulder(
    g: &Geometry<6>,
    pose: &Pose,
    wrist: &Wrist,
    (r06, w0, w): (M3, V3, V3),
    free: &[f64; 6],
    out: &mut Candidates<6, 8>,
) {
    let [h1, h2, h3, ..] = g.h;
    let (p12, p23, p34) = (g.p[1] - g.p[0], g.p[2] - g.p[1], w0 - g.p[2]);
    let p16 = w - g.p[0];
    let t3 = sp4(&h1, &p34, &h3, h1.dot(&(p16 - p12 - p23)), free[2]);
    for q3 in t3.as_slice() {
        let r3 = q3.rot(&h3);
        let v = p23 + r3 * p34;
        let t2 = sp3(
            &flat(&h1, &v),
            &flat(&h1, &(-p12)),
            &h2,
            flat(&h1, &p16).norm(),
            free[1],
        );
        for q2 in t2.as_slice() {
            let r2 = q2.rot(&h2);
            let (q1, f1) = sp1(&(p12 + r2 * v), &p16, &h1, free[0]);
            let r36 = (rot(&h1, q1) * r2 * r3).transpose() * r06;
            let q123 = [q1, q2.theta, q3.theta];
            let wrist_of = (wrist.target(&r36), || r36);
            // Where the axes are one line, SP3 leaves q2 free (a singular configuration of
            // the locked arm); 0.4 mm apart (the URDF's iiwa) the branches are regular.
            // Parallel to |h1 × h2| ≤ 1e-12 rad: the decomposition's error is below that
            // times the arm's lengths.
            let fit = t3.fit.and(t2.fit).and(f1);
            with_wrist((g, pose), wrist, q123, wrist_of, fit, free, out);
        }
    }
}

/// **Spherical wrist, h1 ∩ h2, joint 3 prismatic** (the Stanford arm):
///
/// 1. `p16 = w − c12`; with `u = p23 + p34`, q3 from `‖u + q3 h3‖ = ‖p16‖` (a quadratic)
/// 2. (q1, q2) — SP2: `rot(−h1, q1) p16 = rot(h2, q2) (u + q3 h3)`
/// 3. wrist as above.
pub fn spherical_two_intersecting_prismatic(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let wrist = Wrist::new(g, pair);
    let (r06, w0, w) = wrist_centre(g, pose);
    let c12 = meet(g, 0, 1);
    let [h1, h2, ..] = g.h;
    shoulder_slide(g, c12, w0, w, free, |q1, q2, q3, fit| {
        // Joint 3 slides: it turns nothing.
        let r36 = (q1.rot(&h1) * q2.rot(&h2)).transpose() * r06;
        let q123 = [q1.theta, q2.theta, q3];
        let wrist_of = (wrist.target(&r36), || r36);
        with_wrist((g, pose), &wrist, q123, wrist_of, fit, free, out);
    });
}
