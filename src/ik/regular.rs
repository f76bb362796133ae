//! Closed-form IK of a **regular** pose — every subproblem on the way has two distinct
//! exact roots (or, for a branch whose wrist centre the elbow cannot reach, its one
//! least-squares root): no singular configuration, no angle left free — with the branches
//! of each level side by side in [`Lanes`], and every joint angle from one batch of
//! `atan2` at the end.
//!
//! The derivation is the family's ([`super::families`]): the same subproblems in the same
//! order, the same decisions (exact, double root, least squares), with what each level
//! needs of its roots — their sines and cosines, which the subproblems give algebraically
//! — for all branches at once. The angles are only printed into the solutions, so their
//! `atan2` wait for the end: twenty-odd in one pass. Almost every pose is regular; the
//! family's solver runs this first and, where it returns `None` (a double root, a free
//! angle, a circle of radius zero in some lane), solves the pose branch by branch as
//! before, with `free` values and fits. The solutions are those of the branch-by-branch
//! solve, in the same order, to rounding (`tests/ik_regular.rs` compares them) — but for
//! the branches whose elbow misses a pose another branch reaches by more than `FAR`
//! (2√3 · [`NEAR_MISS`]): `finish` would check them with the robot's `fk` only to leave
//! them out (no answer to a pose the arm reaches), so the lanes leave them out first
//! (in the h1 ∩ h2 family, the branches whose shoulder misses: its SP2's circles apart).
//! For a caller that keeps only reaching solutions ([`Candidates::reaching_only`]: a
//! reachability map), they are left out at a pose no branch reaches too.
//!
//! Here: the UR family ([`three_parallel_two_intersecting`]) and the PUMA family
//! ([`spherical_two_parallel`]); in `regular/spherical_two_intersecting.rs` the family
//! whose shoulder axes meet ([`spherical_two_intersecting()`]: the iiwa, and the Panda
//! read from the tool).

use super::geometry::{flat, Geometry, Orbit, Pose, M3, V3};
use super::lanes::{Lanes, Vectors};
use super::setup::{ThreeParallel, WristArm};
use super::solutions::{Candidates, NEAR_MISS};
use super::subproblems::{
    roots_of, sp1_fit_lanes, wrap, Fit, Plane, RootLanes, Sp3Lanes, Sp4Lanes,
};
use crate::math::fast_atan2_n;
use core::f64::consts::PI;

/// Calls the lanes solver `$solver(g, pose, out)` built for AVX2 where the CPU has it
/// (x86_64 with `std`, which can ask at run time), else as built for the target: four
/// `f64` lanes per register instead of SSE2's two, and three-operand instructions (no
/// register copies). The same operations in the same order, so the same bits (no fused
/// multiply-add: Rust never contracts `a * b + c`); the tests compare both builds.
macro_rules! best_build {
    ($solver:ident($g:ident, $pose:ident, $out:ident)) => {{
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            /// # Safety
            /// The CPU must have AVX2.
            #[target_feature(enable = "avx2")]
            unsafe fn avx2(g: &Geometry<6>, pose: &Pose, out: &mut Candidates<6, 8>) -> Option<()> {
                $solver(g, pose, out)
            }
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (asked just now; `std` caches the answer).
                return unsafe { avx2($g, $pose, $out) };
            }
        }
        $solver($g, $pose, $out)
    }};
}

// After `best_build!`, which its solver uses.
mod spherical_two_intersecting;

pub use spherical_two_intersecting::spherical_two_intersecting;

/// `v` in the coordinates of `plane` (`e1·v`, `e2·v`, `k·v`).
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn coords(plane: &Plane, v: &V3) -> V3 {
    let s = plane.split(v);
    V3::new(s.v[0], s.v[1], s.along)
}

/// `rot(k, σ θ) x` for the angles with cosines `c` and sines `s`, `σ = ±1` (`σ = −1`:
/// `R(θ)ᵀ x`), in the coordinates of `plane`: `x`'s orbit about the unit `k`, both mapped
/// first (an orthonormal basis with `e1 × e2 = k`: dot and cross products are the same in
/// its coordinates).
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn turned<const L: usize>(
    plane: &Plane,
    k: &V3,
    x: &V3,
    (c, s): (Lanes<L>, Lanes<L>),
    sigma: f64,
) -> Vectors<L> {
    Orbit::new(&coords(plane, k), &coords(plane, x)).at_lanes(c, s * sigma)
}

/// `rot(k, θ) v` for vectors and angles in lanes (Rodrigues), `k` fixed.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn rotate<const L: usize>(k: &V3, v: &Vectors<L>, (c, s): (Lanes<L>, Lanes<L>)) -> Vectors<L> {
    let along = v.dot_fixed(k) * (Lanes::splat(1.0) - c);
    let kv = Vectors::splat(k).cross(v);
    Vectors {
        x: v.x * c + kv.x * s + along * k.x,
        y: v.y * c + kv.y * s + along * k.y,
        z: v.z * c + kv.z * s + along * k.z,
    }
}

/// A turn about the plane's own axis: a 2-D rotation of the in-plane coordinates by the
/// angles with cosines `c` and sines `s`.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn about_axis<const L: usize>(v: &Vectors<L>, c: Lanes<L>, s: Lanes<L>) -> Vectors<L> {
    Vectors {
        x: c * v.x - s * v.y,
        y: s * v.x + c * v.y,
        z: v.z,
    }
}

/// SP1 in the plane — `rot(k, θ) a = b` with both in the plane's coordinates — up to its
/// `atan2`: `(y, x)` and which lanes are exact (as `sp1_planar_sides` decides); `None`
/// where the angle is free in some lane.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn planar_sides<const L: usize>(
    a: &Vectors<L>,
    b: &Vectors<L>,
) -> Option<(Lanes<L>, Lanes<L>, [bool; L])> {
    let (na, nb) = (a.x * a.x + a.y * a.y, b.x * b.x + b.y * b.y);
    let exact = sp1_fit_lanes([(na, na + a.z * a.z), (nb, nb + b.z * b.z)], a.z - b.z)?;
    Some((a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y, exact))
}

/// SP1 — `rot(k, θ) p1 = p2` — up to its `atan2`, in lanes: `(y, x)` and which lanes are
/// exact (as `sp1_sides` decides); `None` where the angle is free in some lane.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn sides<const L: usize>(
    p1: &Vectors<L>,
    p2: &Vectors<L>,
    k: &V3,
) -> Option<(Lanes<L>, Lanes<L>, [bool; L])> {
    let (a, b) = (p1.off_axis(k), p2.off_axis(k));
    let lengths = [(a.dot(&a), p1.dot(p1)), (b.dot(&b), p2.dot(p2))];
    let exact = sp1_fit_lanes(lengths, p1.dot_fixed(k) - p2.dot_fixed(k))?;
    Some((a.cross(&b).dot_fixed(k), a.dot(&b), exact))
}

/// q1 — SP4: `h2ᵀ rot(−h1, q1) p16 = d`, its circle, its two distinct exact roots, and
/// their cosines and sines as the two lanes of the shoulders (`None` otherwise: the wrist
/// centre out of reach, or on axis 1).
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn shoulder(
    h1: &V3,
    h2: &V3,
    p16: &V3,
    d: f64,
) -> Option<(Sp4Lanes, RootLanes<1>, (Lanes<2>, Lanes<2>))> {
    let circle = Sp4Lanes::new(h2, p16, &(-h1));
    let roots = circle.solve(Lanes([d]), Lanes([d.abs()]))?;
    let (c, s) = (roots.cos, roots.sin);
    let q1 = (Lanes([c[0].0[0], c[1].0[0]]), Lanes([s[0].0[0], s[1].0[0]]));
    roots.exact[0].then_some((circle, roots, q1))
}

/// An elbow out of reach by more than this misses the pose by more than [`NEAR_MISS`]:
/// where the rest of the branch is solved exactly, its orientation is the pose's and its
/// position error is the elbow's miss, whose largest coordinate is at least its length
/// over √3 (twice that here, for rounding).
const FAR: f64 = 2.0 * 1.732_050_807_568_877_2 * NEAR_MISS;

/// Of the `misses` lanes — an elbow out of reach, the rest of the branch exact — those
/// whose miss exceeds [`FAR`] where some branch reaches the pose, or the caller keeps
/// only reaching solutions (`reached`, asked only if there are such lanes): `finish`
/// would check their branches only to leave them out, as no answer to a pose the arm
/// reaches, or as none the caller keeps ([`Candidates::reaching_only`]). None otherwise
/// (a pose out of reach keeps every branch's nearest).
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn far_elbows<const L: usize>(
    elbow: &Sp3Lanes,
    d2: Lanes<L>,
    misses: [bool; L],
    reached: impl FnOnce() -> bool,
) -> [bool; L] {
    /// Out of line: the solver itself only tests the flags (the UR5 needs this on about
    /// one pose in four, the PUMA 560 never).
    #[inline(never)]
    fn far<const L: usize>(elbow: &Sp3Lanes, d2: Lanes<L>, misses: [bool; L]) -> [bool; L] {
        let miss = elbow.miss(d2);
        core::array::from_fn(|i| misses[i] && miss.0[i] > FAR)
    }
    if misses.contains(&true) && reached() {
        far(elbow, d2, misses)
    } else {
        [false; L]
    }
}

/// `(cos, sin)` of the angles `atan2(y, x)`, without the angles.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn direction<const L: usize>(y: Lanes<L>, x: Lanes<L>) -> (Lanes<L>, Lanes<L>) {
    let inv = Lanes::splat(1.0) / (x * x + y * y).sqrt();
    (x * inv, y * inv)
}

/// A spherical orthogonal wrist (`WristPair::HalfTurn`) of four branches side by side,
/// up to its `atan2`: q5's roots, and q4 and q6 for q5's first root, each `(y, x,
/// exact)` — the second root's q4 and q6 are the first's turned by half turns.
struct WristLanes {
    /// q5's circle (its angle φ: [`Sp4Lanes::phi_sides`]).
    circle: Sp4Lanes,
    q5: RootLanes<4>,
    q4: (Lanes<4>, Lanes<4>, [bool; 4]),
    q6: (Lanes<4>, Lanes<4>, [bool; 4]),
}

/// The wrist's level: q5 — SP4: `h4ᵀ rot(h5, q5) h6 = h4ᵀ R36 h6`, then q4 — SP1:
/// `rot(h4, q4) R5 h6 = R36 h6` and q6 — SP1: `rot(h6, q6) R36ᵀ h4 = R5ᵀ h4`, from what
/// each branch needs of `R36`: `R36 h6` in the coordinates `seen` maps a base-frame vector
/// to (a plane's, or the base frame itself), and `R36ᵀ h4` in the base frame. `None`
/// where q5 is not two distinct exact roots in every lane, or q4 or q6 is free in one.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn wrist(
    [h4, h5, h6]: [V3; 3],
    seen: impl Fn(&V3) -> V3,
    r36_h6: &Vectors<4>,
    r36t_h4: &Vectors<4>,
) -> Option<WristLanes> {
    let h4_seen = seen(&h4);
    let circle = Sp4Lanes::new(&h4, &h6, &h5);
    let d5 = r36_h6.dot_fixed(&h4_seen);
    let q5 = circle.solve(d5, d5.map(f64::abs))?;
    if q5.exact.contains(&false) {
        return None;
    }
    let (c5, s5) = (q5.cos[0], q5.sin[0]);
    let r5_h6 = Orbit::new(&seen(&h5), &seen(&h6)).at_lanes(c5, s5);
    let q4 = sides(&r5_h6, r36_h6, &h4_seen)?;
    let r5t_h4 = Orbit::new(&h5, &h4).at_lanes(c5, -s5);
    let q6 = sides(r36t_h4, &r5t_h4, &h6)?;
    Some(WristLanes { circle, q5, q4, q6 })
}

/// The two candidates of one arm branch `q123` with an orthogonal wrist: `(q4, q5⁺, q6)`
/// and `(q4 + π, q5⁻, q6 + π)`.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn push_wrist_pair(
    out: &mut Candidates<6, 8>,
    [q1, q2, q3]: [f64; 3],
    (q4, [q5_plus, q5_minus], q6): (f64, [f64; 2], f64),
    fit: Fit,
) {
    out.push([q1, q2, q3, q4, q5_plus, q6], fit);
    out.push([q1, q2, q3, wrap(q4 + PI), q5_minus, wrap(q6 + PI)], fit);
}

/// **h2 ∥ h3 ∥ h4, h5 ∩ h6** with an orthogonal wrist (`WristPair::HalfTurn`), for a
/// regular pose: the steps of `families::three_parallel_two_intersecting`, level by level
/// — the two shoulders (q1), then per shoulder q5's first root, θ and q6 (the second root
/// by half turns), then the four elbows' SP3, then the eight q2. The candidates go to
/// `out` (empty before, and left untouched unless the pose is regular), but for branches
/// with a far elbow (see the module doc); `None` where a level is not regular in some
/// lane.
pub fn three_parallel_two_intersecting(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    best_build!(three_parallel_two_intersecting_lanes(g, pose, out))
}

/// [`three_parallel_two_intersecting`] itself, inlined into each of its builds.
#[inline(always)]
fn three_parallel_two_intersecting_lanes(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    let set_up = ThreeParallel::new(g, pose);
    let ([h1, h2, h3, _, h5, h6], [p12, p23, p34, p45]) = (set_up.h, set_up.links);
    let (s3, s4, r06, p16) = (set_up.s3, set_up.s4, set_up.r06, set_up.p16);
    // 2. q1 — SP4: h2ᵀ rot(−h1, q1) p16 = h2ᵀ (p12 + p23 + p34 + p45).
    let (shoulder, t1, q1) = shoulder(&h1, &h2, &p16, h2.dot(&(p12 + p23 + p34 + p45)))?;
    // The shoulders' lanes: R1ᵀ of what the rest needs of the target, in the coordinates
    // of the plane ⟂ h2 (turns about h2 ∥ h3 ∥ h4 are 2-D rotations there).
    let plane = Plane::new(&h2);
    let arm = turned(&plane, &h1, &p16, q1, -1.0) - Vectors::splat(&coords(&plane, &p12));
    let t5 = turned(&plane, &h1, &(r06 * h5), q1, -1.0);
    let t6 = turned(&plane, &h1, &(r06 * h6), q1, -1.0);
    // 3. q5 — SP4: h2ᵀ rot(h5, q5) h6 = h2ᵀ R1ᵀ R06 h6.
    let wrist5 = Sp4Lanes::new(&h2, &h6, &h5);
    let q5 = wrist5.solve(t6.z, t6.z.map(f64::abs))?;
    if q5.exact.contains(&false) {
        return None;
    }
    let q5_first = (q5.cos[0], q5.sin[0]);
    // 4. θ — SP1 in the plane: rot(h2, θ) R5 h6 = R1ᵀ R06 h6.
    let r5_h6 = turned(&plane, &h5, &h6, q5_first, 1.0);
    let (theta_y, theta_x, theta_exact) = planar_sides(&r5_h6, &t6)?;
    let (ct, st) = direction(theta_y, theta_x);
    // 7. q6 — SP1: rot(h6, q6) h5 = R5ᵀ R14ᵀ (R1ᵀ R06 h5), with R14 = rot(h2, θ); with
    // a = h5 off h6, its sides are `(R5 (h6 × a))·x`, `(R5 a)·x` for x = R14ᵀ R1ᵀ R06 h5.
    let x = about_axis(&t5, ct, -st);
    let a6 = flat(&h6, &h5);
    // R5 (h6 × a) = R5 h6 × R5 a.
    let r5_a6 = turned(&plane, &h5, &a6, q5_first, 1.0);
    let r5_c6 = r5_h6.cross(&r5_a6);
    let (q6_y, q6_x, along) = (r5_c6.dot(&x), r5_a6.dot(&x), r5_h6.dot(&x));
    // x's part off h6, squared, from its coordinates along a and h6 × a (both ⟂ h6, of
    // length |a|): no cancellation near the wrist singularity, as |x|² − (h6·x)² has.
    let na6 = a6.norm_squared();
    let off6 = (q6_x * q6_x + q6_y * q6_y) * (1.0 / na6);
    let q6_exact = sp1_fit_lanes(
        [
            (Lanes::splat(na6), Lanes::splat(h5.norm_squared())),
            (off6, off6 + along * along),
        ],
        Lanes::splat(h6.dot(&h5)) - along,
    )?;
    if theta_exact.contains(&false) || q6_exact.contains(&false) {
        return None;
    }
    // 8. q5's second root: (θ + π, q6 + π). Four branches (q1, q5) from here on.
    let (ct4, st4): (Lanes<4>, Lanes<4>) = (Lanes::interleave(ct, -ct), Lanes::interleave(st, -st));
    // 5. q3 — SP3 in the plane: ‖p23 + rot(h3, q3) p34‖ = ‖arm − rot(h2, θ) p45‖; a
    // branch whose wrist centre is out of the elbow's reach has one least-squares q3.
    let p45_ = Vectors::splat(&coords(&plane, &p45));
    let reach = arm.twice::<4>() - about_axis(&p45_, ct4, st4);
    let elbow = Sp3Lanes::new(&flat(&h2, &p34), &flat(&h2, &(-p23)), &h3);
    let d2 = reach.x * reach.x + reach.y * reach.y;
    let q3 = elbow.solve(d2)?;
    // 6. q2 — SP1 in the plane: rot(h2, q2) (p23 + R3 p34) = reach. Eight branches.
    let (c3, s3_): (Lanes<8>, Lanes<8>) = (
        Lanes::interleave(q3.cos[0], q3.cos[1]),
        Lanes::interleave(q3.sin[0], q3.sin[1]),
    );
    let (p23_, p34_) = (coords(&plane, &p23), coords(&plane, &p34));
    let arm3 = about_axis(&Vectors::splat(&p34_), c3, s3_ * s3) + Vectors::splat(&p23_);
    let (q2_y, q2_x, q2_exact) = planar_sides(&arm3, &reach.twice::<8>())?;
    // Every angle in one pass: q5's d (2), θ (2), q6 (2), q3's d (4), q2 (8), q1's d,
    // and the angles φ of the three circles cut.
    let mut ys = [0.0; 22];
    let mut xs = [0.0; 22];
    for (at, (y, x)) in [
        (0, (q5.y, q5.x)),
        (2, (theta_y, theta_x)),
        (4, (q6_y, q6_x)),
    ] {
        ys[at..at + 2].copy_from_slice(&y.0);
        xs[at..at + 2].copy_from_slice(&x.0);
    }
    ys[6..10].copy_from_slice(&q3.y.0);
    xs[6..10].copy_from_slice(&q3.x.0);
    ys[10..18].copy_from_slice(&q2_y.0);
    xs[10..18].copy_from_slice(&q2_x.0);
    (ys[18], xs[18]) = wrist5.phi_sides();
    (ys[19], xs[19]) = elbow.phi_sides();
    (ys[20], xs[20]) = (t1.y.0[0], t1.x.0[0]);
    (ys[21], xs[21]) = shoulder.phi_sides();
    let t = fast_atan2_n(ys, xs);
    // Every lane's wrist is exact here: a branch is, where its elbow and q2 are.
    let exact = |l: usize| q3.exact[l / 2] && q2_exact[l];
    let only_reaching = out.wants_reaching_only();
    let far = far_elbows(&elbow, d2, q3.exact.map(|e| !e), || {
        only_reaching || (0..8).any(exact)
    });
    for (i, q1) in roots_of(t[21], t[20]).into_iter().enumerate() {
        let [q5_plus, q5_minus] = roots_of(t[18], t[i]);
        let (theta, q6) = (t[2 + i], t[4 + i]);
        let wrists = [
            (theta, q5_plus, q6),
            (wrap(theta + PI), q5_minus, wrap(q6 + PI)),
        ];
        for (k, (theta, q5, q6)) in wrists.into_iter().enumerate() {
            let j = 2 * i + k;
            if far[j] {
                continue;
            }
            let roots = if q3.exact[j] { 2 } else { 1 };
            for (r, q3_) in roots_of(t[19], t[6 + j])
                .into_iter()
                .take(roots)
                .enumerate()
            {
                let q2 = t[10 + 2 * j + r];
                let q4 = wrap(s4 * (theta - q2 - s3 * q3_));
                let fit = if exact(2 * j + r) {
                    Fit::Exact
                } else {
                    Fit::LeastSquares
                };
                out.push([q1, q2, q3_, q4, q5, q6], fit);
            }
        }
    }
    Some(())
}

/// **Spherical wrist, h2 ∥ h3** with an orthogonal wrist (`WristPair::HalfTurn`), for a
/// regular pose: the steps of `families::spherical_two_parallel`, level by level — the
/// two shoulders (q1), their elbows' SP3, the four q2, then the four wrists' q5 (first
/// root), q4 and q6 (the second root by half turns). The candidates go to `out` (empty
/// before, and left untouched unless the pose is regular), but for branches with a far
/// elbow (see the module doc); `None` where a level is not regular in some lane.
pub fn spherical_two_parallel(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    best_build!(spherical_two_parallel_lanes(g, pose, out))
}

/// [`spherical_two_parallel`] itself, inlined into each of its builds.
#[inline(always)]
fn spherical_two_parallel_lanes(
    g: &Geometry<6>,
    pose: &Pose,
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    // 1. The wrist centre, from joint 1.
    let WristArm {
        r06,
        links: [p12, p23, p34],
        p16,
    } = WristArm::new(g, pose);
    let [h1, h2, h3, h4, h5, h6] = g.h;
    let s3 = h3.dot(&h2).signum();
    // 2. q1 — SP4: h2ᵀ rot(−h1, q1) p16 = h2ᵀ (p12 + p23 + p34).
    let (shoulder, t1, q1) = shoulder(&h1, &h2, &p16, h2.dot(&(p12 + p23 + p34)))?;
    // The shoulders' lanes, in the coordinates of the plane ⟂ h2.
    let plane = Plane::new(&h2);
    let to_plane = |v: &V3| coords(&plane, v);
    let v = turned(&plane, &h1, &p16, q1, -1.0) - Vectors::splat(&to_plane(&p12));
    let x6 = turned(&plane, &h1, &(r06 * h6), q1, -1.0);
    // 3. q3 — SP3 in the plane: ‖p23 + rot(h3, q3) p34‖ = ‖R1ᵀ p16 − p12‖; a shoulder
    // whose wrist centre is out of the elbow's reach has one least-squares q3.
    let elbow = Sp3Lanes::new(&flat(&h3, &p34), &flat(&h3, &(-p23)), &h3);
    let d2 = v.x * v.x + v.y * v.y;
    let q3 = elbow.solve(d2)?;
    // 4. q2 — SP1 in the plane: rot(h2, q2) (p23 + R3 p34) = R1ᵀ p16 − p12. Four
    // branches (q1, q3) from here on.
    let (c3, s3_): (Lanes<4>, Lanes<4>) = (
        Lanes::interleave(q3.cos[0], q3.cos[1]),
        Lanes::interleave(q3.sin[0], q3.sin[1]),
    );
    let p34_ = Vectors::splat(&to_plane(&p34));
    let arm3 = about_axis(&p34_, c3, s3_ * s3) + Vectors::splat(&to_plane(&p23));
    let (q2_y, q2_x, q2_exact) = planar_sides(&arm3, &v.twice::<4>())?;
    let (c2, s2) = direction(q2_y, q2_x);
    // R2 R3 = rot(h2, q2 + σ q3).
    let (c23, s23) = (c2 * c3 - s2 * s3_ * s3, s2 * c3 + c2 * s3_ * s3);
    // 5. The wrist: R36 h6 = R23ᵀ R1ᵀ R06 h6 (in the plane's coordinates) and R36ᵀ h4 =
    // R06ᵀ R1 R23 h4 (in the base frame).
    let r36_h6 = about_axis(&x6.twice::<4>(), c23, -s23);
    let h4_ = about_axis(&Vectors::splat(&to_plane(&h4)), c23, s23);
    let h4_23 = h4_.mul_by(&M3::from_columns(&plane.basis()));
    let (c1, s1) = q1;
    let r36t_h4 = rotate(&h1, &h4_23, (c1.twice(), s1.twice())).tr_mul_by(&r06);
    // q5, q4, q6, with R36 h6 in the plane's coordinates.
    let WristLanes {
        circle: wrist5,
        q5,
        q4: (q4_y, q4_x, q4_exact),
        q6: (q6_y, q6_x, q6_exact),
    } = wrist([h4, h5, h6], to_plane, &r36_h6, &r36t_h4)?;
    let exact = |j: usize| q3.exact[j / 2] && q2_exact[j] && q4_exact[j] && q6_exact[j];
    // An elbow out of reach has one branch, j = 2 i; its orientation is exact where its
    // q4 and q6 are.
    let misses: [bool; 2] =
        core::array::from_fn(|i| !q3.exact[i] && q4_exact[2 * i] && q6_exact[2 * i]);
    let only_reaching = out.wants_reaching_only();
    let far = far_elbows(&elbow, d2, misses, || only_reaching || (0..4).any(exact));
    // Every angle in one pass: q3's d (2), q2 (4), q5's d (4), q4 (4), q6 (4), q1's d,
    // and the angles φ of the three circles cut.
    let mut ys = [0.0; 22];
    let mut xs = [0.0; 22];
    ys[..2].copy_from_slice(&q3.y.0);
    xs[..2].copy_from_slice(&q3.x.0);
    for (at, (y, x)) in [
        (2, (q2_y, q2_x)),
        (6, (q5.y, q5.x)),
        (10, (q4_y, q4_x)),
        (14, (q6_y, q6_x)),
    ] {
        ys[at..at + 4].copy_from_slice(&y.0);
        xs[at..at + 4].copy_from_slice(&x.0);
    }
    (ys[18], xs[18]) = elbow.phi_sides();
    (ys[19], xs[19]) = wrist5.phi_sides();
    (ys[20], xs[20]) = (t1.y.0[0], t1.x.0[0]);
    (ys[21], xs[21]) = shoulder.phi_sides();
    let t = fast_atan2_n(ys, xs);
    for (i, q1) in roots_of(t[21], t[20]).into_iter().enumerate() {
        if far[i] {
            continue;
        }
        let roots = if q3.exact[i] { 2 } else { 1 };
        for (r, q3_) in roots_of(t[18], t[i]).into_iter().take(roots).enumerate() {
            let j = 2 * i + r;
            let q5 = roots_of(t[19], t[6 + j]);
            let fit = if exact(j) {
                Fit::Exact
            } else {
                Fit::LeastSquares
            };
            push_wrist_pair(out, [q1, t[2 + j], q3_], (t[10 + j], q5, t[14 + j]), fit);
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::geometry::examples::{iiwa_locked, puma, ur5};
    use crate::ik::geometry::rot;

    /// Poses of `g` from seeded configurations, some moved out of reach.
    fn poses(g: &Geometry<6>) -> impl Iterator<Item = Pose> + '_ {
        let mut rng = crate::ik::XorShift64::new(31);
        (0..2000).map(move |n| {
            let q: [f64; 6] = core::array::from_fn(|_| 6.0 * rng.next_f64() - 3.0);
            let mut pose = g.fk(&q);
            if n % 4 == 3 {
                pose.p += rot(&V3::z(), q[0]) * V3::x() * 0.2;
            }
            pose
        })
    }

    /// The build the entry points choose (AVX2 where the CPU has it) gives the baseline
    /// build's candidates bit for bit.
    #[test]
    fn the_chosen_build_is_the_baseline_bit_for_bit() {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        std::println!("AVX2: {}", std::is_x86_feature_detected!("avx2"));
        type Solve = fn(&Geometry<6>, &Pose, &mut Candidates<6, 8>) -> Option<()>;
        let solvers: [(Geometry<6>, Solve, Solve); 3] = [
            (
                ur5(),
                |g, p, o| three_parallel_two_intersecting_lanes(g, p, o),
                three_parallel_two_intersecting,
            ),
            (
                puma(),
                |g, p, o| spherical_two_parallel_lanes(g, p, o),
                spherical_two_parallel,
            ),
            (
                iiwa_locked(),
                |g, p, o| spherical_two_intersecting::spherical_two_intersecting_lanes(g, p, o),
                spherical_two_intersecting,
            ),
        ];
        for (g, baseline, chosen) in solvers {
            let mut solved = 0;
            for pose in poses(&g) {
                let (mut a, mut b) = (Candidates::default(), Candidates::default());
                let (ra, rb) = (baseline(&g, &pose, &mut a), chosen(&g, &pose, &mut b));
                assert_eq!(ra, rb);
                solved += usize::from(ra.is_some());
                assert_eq!(a.as_slice().len(), b.as_slice().len());
                for (x, y) in a.as_slice().iter().zip(b.as_slice()) {
                    assert_eq!(x.fit, y.fit);
                    assert_eq!(x.q.map(f64::to_bits), y.q.map(f64::to_bits), "{pose:?}");
                }
            }
            assert!(solved > 1500, "{solved}");
        }
    }
}
