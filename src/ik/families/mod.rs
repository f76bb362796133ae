//! The arm families with closed-form IK from subproblems SP1–SP4 (quadratics at most),
//! after IK-Geo (Elias & Wen) and EAIK (Ostermeier et al.). The engine decides at
//! expansion time, exactly, which family a robot belongs to; these functions solve a pose
//! for a [`Geometry`] that has the family's structure.
//!
//! Each takes `free`: the joint values used where the pose leaves a joint undetermined
//! (a singular configuration — UR or spherical wrist with `h4 ∥ h6`, wrist centre on
//! axis 1). `ik_near` passes the current configuration, so the answer is continuous. Each
//! pushes its candidates into the caller's `out` (empty before): the generated `ik` keeps
//! them on its stack, where `finish` reads them.
//!
//! Joint numbers in the docs are 1-based, as in the robot's tables; `h`, `p` indices are
//! 0-based.

use super::geometry::{flat, meet, orthogonal, rot, Angle, Geometry, Orbit, Pose, M3, V3};
use super::regular;
use super::setup::{wrist_centre, ThreeParallel};
use super::solutions::Candidates;
use super::subproblems::{
    half_turn, sp1, sp1_angle, sp1_angles_2, sp1_from_sides, sp1_planar_angle, sp1_planar_sides,
    sp1_sides, sp2, sp3, sp4, wrap, Fit, Plane, Sp3, Sp4,
};
use core::f64::consts::PI;

/// How a solver finds the second of a wrist's two solutions (the two roots of q5).
///
/// Write the last three rotations as `rot(a, θa) rot(h5, q5) rot(h6, q6)`, with `a` = h4
/// for a spherical wrist and `a` = h2 ∥ h3 ∥ h4 for the UR family (θa = q4, or θ = q2 ±
/// q3 ± q4). When `a ⟂ h5` and `h5 ⟂ h6` at `q = 0` — an orthogonal wrist — `h6 =
/// rot(h5, o) a` for some `o`, `rot(a, π) rot(h5, x) = rot(h5, −x) rot(a, π)` and
/// `rot(a, π) rot(h6, π) = rot(h5, −2o)`, so `(θa + π, −q5 − 2o, q6 + π)` is the other
/// solution: the other root of q5's equation (`φ ± d` with `φ = −o`) takes θa and q6 from
/// the first by half turns, without a subproblem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WristPair {
    /// Both solutions from the subproblems (any wrist geometry).
    Solve,
    /// The second is the first turned by half turns about `a` and `h6` (the engine proved
    /// the wrist orthogonal, exactly, at expansion time).
    HalfTurn,
}

/// The spherical wrist (joints 4, 5, 6 meet in a point), set up once per solve: its axes,
/// the circle SP4 cuts for q5 (the same for every arm branch), how the second root is
/// found.
struct Wrist {
    h: [V3; 3],
    q5: Sp4,
    pair: WristPair,
    /// `R5 h6` and `R5ᵀ h4`: h6's and h4's orbits about h5.
    h6_about_h5: Orbit,
    h4_about_h5: Orbit,
}

impl Wrist {
    fn new(g: &Geometry<6>, pair: WristPair) -> Wrist {
        let h = [g.h[3], g.h[4], g.h[5]];
        // h4ᵀ rot(h5, q5) h6 = h4ᵀ R36 h6.
        let q5 = Sp4::new(&h[0], &h[2], &h[1]);
        Wrist {
            h,
            q5,
            pair,
            h6_about_h5: Orbit::new(&h[1], &h[2]),
            h4_about_h5: Orbit::new(&h[1], &h[0]),
        }
    }

    /// `(q4, q5, q6)` with `R4 R5 R6 = R36`, from what the wrist needs of `R36`:
    /// `target = (R36 h6, R36ᵀ h4)`; the whole `r36()` only at `h4 ∥ R5 h6`. SP4 for
    /// q5, SP1 for q4 and q6; at `h4 ∥ R5 h6` (q5 at its singular value) q4 is free and q6
    /// is taken from the whole rotation. With [`WristPair::HalfTurn`] the second root of
    /// q5 takes `(q4 + π, q6 + π)` from the first.
    fn solve(
        &self,
        (r36_h6, r36t_h4): (V3, V3),
        r36: impl Fn() -> M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> usize {
        let [h4, h5, h6] = &self.h;
        let t5 = self.q5.solve(h4.dot(&r36_h6), 0.0);
        if self.pair == WristPair::HalfTurn && t5.n == 2 {
            let q5 = t5.angles[0];
            let sides4 = sp1_sides(&self.h6_about_h5.at(&q5), &r36_h6, h4);
            // Two distinct roots: h4 ∦ R5 h6, so q4 is not free.
            if sides4.is_some() {
                // q4 and q6 side by side (q6's SP1 does not need q4).
                let sides6 = sp1_sides(&r36t_h4, &self.h4_about_h5.back(&q5), h6);
                let [(q4, f4), (q6, f6)] = sp1_angles_2([sides4, sides6], free);
                let fit = t5.fit.and(f4).and(f6);
                out[0] = ([q4, q5.theta, q6], fit);
                out[1] = ([wrap(q4 + PI), t5.angles[1].theta, wrap(q6 + PI)], fit);
                return 2;
            }
        }
        for (o, q5) in out.iter_mut().zip(t5.as_slice()) {
            let (q4, f4) = sp1(&self.h6_about_h5.at(q5), &r36_h6, h4, free[0]);
            let (q6, f6) = if f4 == Fit::Free {
                // Only q4 ± q6 is determined: q4 = free, q6 from R6 = (R4 R5)ᵀ R36.
                let m = (rot(h4, q4) * q5.rot(h5)).transpose() * r36();
                let x = orthogonal(h6);
                sp1(&x, &(m * x), h6, free[1])
            } else {
                // R6 (R36ᵀ h4) = R5ᵀ h4, since R36ᵀ h4 = R6ᵀ R5ᵀ h4.
                sp1(&r36t_h4, &self.h4_about_h5.back(q5), h6, free[1])
            };
            *o = ([q4, q5.theta, q6], t5.fit.and(f4).and(f6));
        }
        t5.n
    }

    /// What [`Wrist::solve`] needs of the rotation `r36`.
    fn target(&self, r36: &M3) -> (V3, V3) {
        (r36 * self.h[2], r36.transpose() * self.h[0])
    }
}

/// Adds the wrist solutions for the arm joints `q123` to `out`; `R36 = (R1 R2 R3)ᵀ R06` is
/// the rotation the wrist must make (a prismatic joint turns nothing), given as
/// `target = (R36 h6, R36ᵀ h4)` and, for a wrist singularity, `r36()`.
fn with_wrist(
    wrist: &Wrist,
    q123: [f64; 3],
    (target, r36): ((V3, V3), impl Fn() -> M3),
    fit: Fit,
    free: &[f64; 6],
    out: &mut Candidates<6, 8>,
) {
    let mut w = [([0.0; 3], Fit::Exact); 2];
    let n = wrist.solve(target, r36, [free[3], free[5]], &mut w);
    for &(q456, f) in &w[..n] {
        let q = [q123[0], q123[1], q123[2], q456[0], q456[1], q456[2]];
        out.push(q, fit.and(f));
    }
}

/// A family's solver for regular poses in lanes (see [`regular`]) and its branch-by-branch
/// solver for every pose.
type Solvers = (
    fn(&Geometry<6>, &Pose, &mut Candidates<6, 8>) -> Option<()>,
    fn(&Geometry<6>, &Pose, &[f64; 6], WristPair, &mut Candidates<6, 8>),
);

/// The candidates of a regular pose from the lanes (for an orthogonal wrist), else those of
/// the branch-by-branch solver, into `out` (empty before).
#[inline]
fn regular_first(
    (lanes, by_branch): Solvers,
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    // The lanes leave `out` untouched where they return `None`.
    if !(pair == WristPair::HalfTurn && lanes(g, pose, out).is_some()) {
        by_branch(g, pose, free, pair, out);
    }
}

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
    let (r06, w0, w) = wrist_centre(g, pose);
    let [h1, h2, h3, ..] = g.h;
    let (p12, p23, p34) = (g.p[1] - g.p[0], g.p[2] - g.p[1], w0 - g.p[2]);
    let p16 = w - g.p[0];
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
            with_wrist(&wrist, q123, (target, r36), fit, free, out);
        }
    }
}

/// **Spherical wrist, h1 ∩ h2** (the shoulder axes meet):
///
/// 1. `p16 = w − c12`, `c12` where axes 1 and 2 meet
/// 2. q3 — SP3: `‖p23 + rot(h3, q3) p34‖ = ‖p16‖`
/// 3. (q1, q2) — SP2: `rot(−h1, q1) p16 = rot(h2, q2) (p23 + R3 p34)`
/// 4. wrist as above.
pub fn spherical_two_intersecting(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    pair: WristPair,
    out: &mut Candidates<6, 8>,
) {
    let wrist = Wrist::new(g, pair);
    let (r06, w0, w) = wrist_centre(g, pose);
    let [h1, h2, h3, ..] = g.h;
    let skew = h1.cross(&h2).norm_squared();
    if skew <= SHOULDER_PARALLEL {
        parallel_shoulder(g, &wrist, (r06, w0, w), free, out);
        return;
    }
    // Nearly parallel: the meeting point is far out (≳ 1e6 × the axes' offset), and the
    // distances through it lose digits. The branches are checked against `fk`.
    let far = if skew <= SHOULDER_FAR {
        Fit::Double
    } else {
        Fit::Exact
    };
    let c12 = meet(g, 0, 1);
    let (p23, p34) = (g.p[2] - c12, w0 - g.p[2]);
    let p16 = w - c12;
    let t3 = sp3(&p34, &(-p23), &h3, p16.norm(), free[2]);
    for q3 in t3.as_slice() {
        let r3 = q3.rot(&h3);
        let arm = p23 + r3 * p34;
        let (t12, n, f12) = sp2(&p16, &arm, &(-h1), &h2, (free[0], free[1]));
        for (q1, q2) in &t12[..n] {
            let r36 = (q1.rot(&h1) * q2.rot(&h2) * r3).transpose() * r06;
            let q123 = [q1.theta, q2.theta, q3.theta];
            let wrist_of = (wrist.target(&r36), || r36);
            with_wrist(&wrist, q123, wrist_of, t3.fit.and(f12).and(far), free, out);
        }
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

/// The spherical-wrist family with the shoulder's axes parallel at this pose (`h2 = σ h1`,
/// possibly one line), so `R1 R2 = rot(h1, q1 + σ q2)`:
///
/// 1. q3 — SP4: `h1ᵀ rot(h3, q3) p34 = h1ᵀ (p16 − p12 − p23)` (turns about h1 keep it)
/// 2. q2 — SP3 in the plane ⟂ h1: `‖p12⊥ + rot(h2, q2) v⊥‖ = ‖p16⊥‖`, `v = p23 + R3 p34`
///    (free when the axes are one line: `p12⊥ = 0`)
/// 3. q1 — SP1: `rot(h1, q1) (p12 + R2 v) = p16`; the wrist as above.
fn parallel_shoulder(
    g: &Geometry<6>,
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
            with_wrist(wrist, q123, wrist_of, fit, free, out);
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
    let [h1, h2, h3, ..] = g.h;
    let u = w0 - c12;
    let p16 = w - c12;
    // q3² + 2 b q3 + c = 0
    let b = h3.dot(&u);
    let c = u.norm_squared() - p16.norm_squared();
    let disc = b * b - c;
    let terms = b * b + u.norm_squared() + p16.norm_squared();
    let merge = super::subproblems::ROOT_MERGE * f64::EPSILON * terms;
    let (roots, fit): ([f64; 2], Fit) = if disc.abs() <= merge {
        ([-b, -b], Fit::Double)
    } else if disc < 0.0 {
        ([-b, -b], Fit::LeastSquares)
    } else {
        let s = crate::math::sqrt(disc);
        ([-b + s, -b - s], Fit::Exact)
    };
    let n3 = if fit == Fit::Exact { 2 } else { 1 };
    for &q3 in &roots[..n3] {
        let arm = u + h3 * q3;
        let (t12, n, f12) = sp2(&p16, &arm, &(-h1), &h2, (free[0], free[1]));
        for (q1, q2) in &t12[..n] {
            // Joint 3 slides: it turns nothing.
            let r36 = (q1.rot(&h1) * q2.rot(&h2)).transpose() * r06;
            let q123 = [q1.theta, q2.theta, q3];
            let wrist_of = (wrist.target(&r36), || r36);
            with_wrist(&wrist, q123, wrist_of, fit.and(f12), free, out);
        }
    }
}

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
    let (r06_h5, r06_h6) = (r06 * h5, r06 * h6);
    let elbow = Sp3::new(&flat(&h2, &p34), &flat(&h2, &(-p23)), &h3);
    // The arm's plane ⟂ h2: turns about h2 ∥ h3 ∥ h4 are 2-D rotations there.
    let plane = Plane::new(&h2);
    let (p23_, p34_, p45_) = (plane.split(&p23), plane.split(&p34), plane.split(&p45));
    for q1 in t1.as_slice() {
        let r1t = q1.rot(&h1).transpose();
        // R1ᵀ R06 h5, R1ᵀ R06 h6: all the wrist needs of the target's rotation.
        let (target_h5, target_h6) = (r1t * r06_h5, r1t * r06_h6);
        let arm = r1t * p16 - p12;
        let arm_ = plane.split(&arm);
        let t5 = wrist5.solve(h2.dot(&target_h6), free[4]);
        // WristPair::HalfTurn: the first root's θ, its fit and q6, for the second root.
        let mut turned: Option<(Angle, Fit, (f64, Fit))> = None;
        for (k, q5) in t5.as_slice().iter().enumerate() {
            // q6 — SP1: R6 h5 = (R14 R5)ᵀ R1ᵀ R06 h5 with R14 = rot(h2, θ): with θ known,
            // one per (q1, q5), whichever elbow.
            let q6_for = |r5: &M3, r14: &M3| {
                let x = r5.transpose() * (r14.transpose() * target_h5);
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
                    let (theta, ft) = sp1_angle(&(r5 * h6), &target_h6, &h2, 0.0);
                    // The arm (q2, q3, q4): θ known (q4 from it), or at the wrist
                    // singularity q4 = free — or, when that q4 puts the wrist out of the
                    // elbow's reach, θ chosen mid-range of what the elbow can reach,
                    // nearest to free's.
                    let mode = if ft == Fit::Free {
                        let q4 = free[3];
                        let known = p34 + rot(&h4, q4) * p45;
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
                    let sides = |q3: &Angle| sp1_planar_sides(&(p23_ + p34_.turn(q3, s3)), &reach);
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
                        let (q2, f2) = sp1(&(p23 + q3.rot(&h3) * known), &arm, &h2, free[1]);
                        let (q6, f6) = q6_for(&r5, &rot(&h2, q2 + s3 * q3.theta + s4 * q4));
                        out.push(
                            [q1.theta, q2, q3.theta, q4, q5.theta, q6],
                            fit.and(t3.fit).and(f2).and(f6),
                        );
                    }
                }
            }
        }
    }
}

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

/// **Planar** — every axis along world z; solves the task rows x, y (with three revolute
/// joints also the angle about z, with a prismatic joint also z):
///
/// 1. with three revolute joints, `ψ = φ − φ0` (the tool's angle about z, minus its
///    angle at `q = 0`) fixes the last one's contribution: `w = p − rot(z, ψ) (pT − p3)`
/// 2. the second revolute joint — SP3 in the xy plane: `‖p12 + rot(h2, q2) v‖ = ‖w − p1‖`
///    (elbow up, elbow down)
/// 3. the first — SP1; the third from ψ; the prismatic joint from z.
///
/// `revolute` lists the revolute joints (2 or 3, 0-based), `prismatic` the prismatic one.
pub fn planar<const N: usize>(
    g: &Geometry<N>,
    pose: &Pose,
    revolute: &[usize],
    prismatic: Option<usize>,
    free: &[f64; N],
    out: &mut Candidates<N, 2>,
) {
    let flat = |v: V3| V3::new(v.x, v.y, 0.0);
    let z = V3::z();
    let sign = |i: usize| g.h[i].z.signum();
    let (a, b) = (revolute[0], revolute[1]);
    let angle = |r: &M3| crate::math::atan2(r[(1, 0)], r[(0, 0)]);
    let psi = angle(&pose.r) - angle(&g.r_tool);
    let (w, end) = match revolute.get(2) {
        Some(&c) => (pose.p - rot(&z, psi) * (g.p_tool - g.p[c]), g.p[c]),
        None => (pose.p, g.p_tool),
    };
    let (p_ab, v, d) = (flat(g.p[b] - g.p[a]), flat(end - g.p[b]), flat(w - g.p[a]));
    let tb = sp3(&v, &(-p_ab), &g.h[b], d.norm(), free[b]);
    for qb in tb.as_slice() {
        let u = p_ab + qb.rot(&g.h[b]) * v;
        let qb = qb.theta;
        let (qa, fa) = sp1(&u, &d, &g.h[a], free[a]);
        let mut q = *free;
        q[a] = qa;
        q[b] = qb;
        if let Some(&c) = revolute.get(2) {
            q[c] = wrap(sign(c) * (psi - sign(a) * qa - sign(b) * qb));
        }
        if let Some(j) = prismatic {
            q[j] = sign(j) * (pose.p.z - g.p_tool.z);
        }
        out.push(q, tb.fit.and(fa));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::geometry::examples::{puma, ur5};
    use crate::ik::subproblems::Fit;

    type Solver = fn(&Geometry<6>, &Pose, &[f64; 6], WristPair, &mut Candidates<6, 8>);

    /// What `solver` puts into an empty set of candidates.
    fn solved(
        solver: Solver,
        g: &Geometry<6>,
        pose: &Pose,
        free: &[f64; 6],
        pair: WristPair,
    ) -> Candidates<6, 8> {
        let mut out = Candidates::default();
        solver(g, pose, free, pair, &mut out);
        out
    }

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
