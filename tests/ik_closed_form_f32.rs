//! The closed-form IK of an f32 robot (the UR5 of `robots/ur5.toml` with `scalar: f32`;
//! at the end, a 5-joint arm, the WidowX 250), which takes f32 poses and returns f32 joint
//! values but solves in f64.
//!
//! IKFast's self-test (random configurations, fixed seed, 20 % of the joints snapped to
//! −π/2, 0 or π/2), on f32 joint values and the f32 robot's own `fk`:
//!
//! - the f32 solutions are the f64 robot's solutions of the same (widened) pose rounded to
//!   f32, bit for bit, with the same flags — the f64 robot built with the f32 robot's
//!   parameters widened, so both solve the same arm;
//! - every exact solution's **f32** `fk` meets the pose within the bound derived below;
//! - away from singularities the generating configuration is among the solutions, within
//!   the joint error the f32 pose's own rounding allows there (derived below);
//! - at singular configurations there is an exact solution, and `ik_near` with the
//!   generating configuration returns it (to the same bound) unless the configuration is
//!   near a second singularity (counted and printed: there the f32 pose does not determine
//!   the joints `ik_near` keeps);
//! - no two solutions are the same f32 configuration.
//!
//! Bounds, with ε = `f32::EPSILON` and `u_i` half an f32 ulp of joint `i`'s value:
//!
//! - f32 `fk` arithmetic: within `4 ε · reach` of the f64 `fk` in position, `4 ε` in the
//!   rotation entries (`robots/tests/f32_error.rs` over 20 000 configurations of every
//!   robot; the firmware check uses the same bounds).
//! - Rounding a joint by `u_i` moves the rotation entries by at most `u_i` and the tool
//!   point by at most `u_i · reach`.
//! - So an exact f64 solution `q*` of the pose, with f64 residual `r*` (measured here),
//!   rounded to f32 has `|fk32(q) − pose| ≤ r* + (4 ε + Σ u_i) · max(1, reach)`.
//! - The generating `q₀` and the solution `q*` it turns into: the pose is `fk32(q₀)`,
//!   within `e = 4 ε · max(1, reach)` per entry of the exact pose of `q₀`, so
//!   `|q* − q₀| ≤ ‖J(q₀)⁻¹‖ · ‖(δp, δθ)‖ ≤ √6 · 2e / σ_min(J(q₀))` to first order (δθ
//!   from rotation entries off by `e`: at most `2e` per component); doubled for the
//!   second-order term, plus `u` for the final rounding.

// Parameter names follow the DH table (`a2`, `d4`).
#![allow(non_snake_case)]

use core::f64::consts::{FRAC_PI_2, TAU};
use kinegen::ik::geometry::Pose;
use kinegen::ik::solutions::{orthonormalized, pose_matrix, EXACT_TOLERANCE_F32};
use kinegen::ik::XorShift64;
use kinegen_robots::Ur5;
use nalgebra::Matrix6;

kinegen::kinematics! {
    /// The UR5 in single precision.
    pub struct Ur5F32 = "robots/ur5.toml";
    scalar: f32,
}

/// Configurations.
const CASES: usize = 10_000;

/// `σ_min(J)` below which a configuration counts as singular (the generating
/// configuration need not be found there; it must have an exact solution instead).
const SINGULAR_SIGMA: f64 = 1e-3;

/// A singular configuration where another singular factor is below this (m for the
/// shoulder factor, 1 for `s3`) is near a second singularity: there the f32 pose's
/// rounding, amplified by 1/factor, leaves the joints `ik_near` would keep undetermined.
const NEAR_SECOND: f64 = 1e-2;

const EPS: f64 = f32::EPSILON as f64;

/// UR5 reach (m): |a2| + |a3| + d1 + d4 + d5 + d6 bounds every lever arm.
fn reach(r: &Ur5F32) -> f64 {
    [r.a2, r.a3, r.d1, r.d4, r.d5, r.d6]
        .iter()
        .map(|x| f64::from(x.abs()))
        .sum()
}

/// Half an f32 ulp of `x`.
fn half_ulp(x: f32) -> f64 {
    let a = x.abs();
    (f64::from(f32::from_bits(a.to_bits() + 1)) - f64::from(a)) / 2.0
}

fn widen4(t: &[[f32; 4]; 4]) -> [[f64; 4]; 4] {
    t.map(|r| r.map(f64::from))
}

/// `max |a − b|` over the top three rows.
fn pose_error(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> f64 {
    (0..3)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| (a[i][j] - b[i][j]).abs())
        .fold(0.0, f64::max)
}

/// Largest joint difference, whole turns removed.
fn joint_gap(a: &[f32; 6], b: &[f32; 6]) -> f64 {
    (0..6)
        .map(|i| {
            let d = f64::from(a[i]) - f64::from(b[i]);
            (d - TAU * (d / TAU).round()).abs()
        })
        .fold(0.0, f64::max)
}

/// A configuration in f32 within ±π (the limits are ±2π; whole turns are the solver's
/// choice), 20 % of the joints snapped to −π/2, 0 or π/2.
fn configuration(rng: &mut XorShift64) -> [f32; 6] {
    let mut q = [0.0f32; 6];
    for x in &mut q {
        let mut v = -core::f64::consts::PI + TAU * rng.next_f64();
        if rng.next_f64() < 0.2 {
            v = [-FRAC_PI_2, 0.0, FRAC_PI_2][(rng.next_u64() % 3) as usize];
        }
        *x = v as f32;
    }
    q
}

fn sigma_min(r: &Ur5, q: &[f64; 6]) -> f64 {
    let j = r.jacobian(q);
    Matrix6::from_fn(|i, k| j[i][k]).singular_values().min()
}

#[test]
fn f32_ur5_ik_is_the_f64_solve_rounded_and_meets_its_own_fk() {
    let r32 = Ur5F32::default();
    // The f64 UR5 with the f32 robot's parameters, widened: the arm the f32 IK solves.
    let r64 = Ur5 {
        d1: f64::from(r32.d1),
        a2: f64::from(r32.a2),
        a3: f64::from(r32.a3),
        d4: f64::from(r32.d4),
        d5: f64::from(r32.d5),
        d6: f64::from(r32.d6),
    };
    let scale = reach(&r32).max(1.0);
    let e = 4.0 * EPS * scale;
    let mut rng = XorShift64::new(32);
    let (mut singular, mut solutions, mut worst_fk, mut worst_found) = (0, 0, 0.0f64, 0.0f64);
    let mut worst_residual = 0.0f64;
    let (mut near_missed, mut doubly) = (0, 0);
    for _ in 0..CASES {
        let q0 = configuration(&mut rng);
        let pose32 = r32.fk(&q0);
        let pose = widen4(&pose32);
        let sols = r32.ik(&pose32);
        // The f32 robot solves for the nearest rotation to its widened pose: so does the
        // reference.
        let target = orthonormalized(&Pose::from_matrix(&pose));
        let reference = r64.ik(&pose_matrix(&target));

        // The f64 solve, rounded.
        let expected = reference.to_f32();
        assert_eq!(sols.len(), expected.len(), "q0 = {q0:?}");
        for (a, b) in sols.iter().zip(expected.iter()) {
            assert_eq!(a.q, b.q, "q0 = {q0:?}");
            let flags = |x: &kinegen::ik::IkBranch<6, f32>| {
                (x.exact, x.singular, x.at_singularity, x.within_limits)
            };
            assert_eq!(flags(a), flags(b), "q0 = {q0:?}");
            // The residual is measured on the product of exponentials for the f32 robot
            // and with the generated f64 `fk` for the f64 one: equal up to f64 rounding.
            let (ra, rb) = (f64::from(a.residual), f64::from(b.residual));
            assert!(
                (ra - rb).abs() <= 1e-12 + 1e-6 * rb,
                "q0 = {q0:?}: {ra:e} vs {rb:e}"
            );
        }
        for (i, a) in sols.iter().enumerate() {
            for b in &sols.as_slice()[i + 1..] {
                assert_ne!(a.q, b.q, "duplicate solutions for {q0:?}");
            }
        }

        // Every exact solution's f32 fk meets the pose.
        for b in sols.exact() {
            let q64 = reference
                .iter()
                .find(|x| x.q.map(|v| v as f32) == b.q)
                .expect("every f32 branch is a rounded f64 branch")
                .q;
            let r_star = pose_error(&r64.fk(&q64), &pose);
            assert!(
                r_star <= EXACT_TOLERANCE_F32,
                "q0 = {q0:?}: r* = {r_star:e}"
            );
            worst_residual = worst_residual.max(r_star);
            let u: f64 = b.q.iter().map(|&x| half_ulp(x)).sum();
            let bound = r_star + (4.0 * EPS + u) * scale;
            let err = pose_error(&widen4(&r32.fk(&b.q)), &pose);
            assert!(
                err <= bound,
                "q0 = {q0:?}: solution {:?} is {err:e} off (bound {bound:e})",
                b.q
            );
            worst_fk = worst_fk.max(err / bound);
        }

        let q0w = q0.map(f64::from);
        let sigma = sigma_min(&r64, &q0w);
        let u_max = q0.iter().map(|&x| half_ulp(x)).fold(0.0, f64::max);
        let tol = 2.0 * 6f64.sqrt() * 2.0 * e / sigma.max(SINGULAR_SIGMA) + 2.0 * u_max;
        let gap = sols
            .exact()
            .map(|b| joint_gap(&b.q, &q0))
            .fold(f64::INFINITY, f64::min);
        solutions += sols.exact().count();
        if sigma >= SINGULAR_SIGMA {
            assert!(
                gap <= tol,
                "q0 = {q0:?} (σ_min {sigma:e}) not among {:?}: nearest {gap:e} > {tol:e}",
                sols.as_slice()
            );
            worst_found = worst_found.max(gap / tol);
        } else {
            singular += 1;
            assert!(
                sols.exact().next().is_some(),
                "singular q0 = {q0:?}: no exact solution"
            );
            let near = r32
                .ik_near(&pose32, &q0)
                .unwrap_or_else(|| panic!("ik_near found nothing for singular {q0:?}"));
            let gap = joint_gap(&near, &q0);
            // Near a second singularity too (another factor under `NEAR_SECOND`), the f32
            // pose does not pin the joints down: counted, not required.
            let second = r64
                .singular_factors(&q0w)
                .iter()
                .filter(|f| f.abs() < NEAR_SECOND)
                .count()
                >= 2;
            if second {
                doubly += 1;
                near_missed += usize::from(gap > tol);
            } else {
                assert!(
                    gap <= tol,
                    "ik_near of singular q0 = {q0:?} is {near:?} ({gap:e} > {tol:e})"
                );
            }
        }
    }
    eprintln!(
        "f32 UR5: {CASES} cases, {singular} singular (σ_min < {SINGULAR_SIGMA:e}), \
         {solutions} exact solutions; largest f64 residual of an exact branch {worst_residual:.2e}; \
         largest fk error / bound {worst_fk:.3}; largest gap to q0 / tolerance {worst_found:.3}; {doubly} near a second singularity, ik_near ≠ q0 in {near_missed} of them"
    );
}

#[test]
fn f32_ur5_ik_rejects_non_finite_input_and_flags_unreachable_poses() {
    let r = Ur5F32::default();
    let mut pose = r.fk(&[0.1, -1.2, 1.4, -0.3, 1.1, 0.2]);
    let mut bad = pose;
    bad[0][3] = f32::NAN;
    assert!(r.ik(&bad).is_empty());
    assert!(r.ik_near(&bad, &[0.0; 6]).is_none());
    // Three metres away: out of reach; the nearest configurations, flagged, finite.
    pose[0][3] = 3.0;
    let sols = r.ik(&pose);
    assert!(!sols.is_empty());
    for b in sols.iter() {
        assert!(!b.exact && b.residual > 1.0 && b.q.iter().all(|x| x.is_finite()));
    }
    assert!(r.ik_near(&pose, &[0.0; 6]).is_none());
}

#[test]
fn f32_ur5_ik_constants_match_the_f64_robot() {
    assert_eq!(Ur5F32::IK_FAMILY, Ur5::IK_FAMILY);
    assert_eq!(Ur5F32::IK_STEPS, Ur5::IK_STEPS);
    assert_eq!(Ur5F32::REVOLUTE, Ur5::REVOLUTE);
    // The geometry is f64 from the widened parameters.
    let g = Ur5F32::default().ik_geometry();
    assert_eq!(g.p[1].z, f64::from(Ur5F32::default().d1));
}

kinegen::kinematics! {
    /// The WidowX 250 (5 joints, the pitch-and-roll family) in single precision.
    pub struct WidowX250F32 = urdf(
        "robots/urdf/wx250.urdf",
        base = "wx250/base_link",
        tip = "wx250/ee_gripper_link"
    );
    scalar: f32,
}

/// A 5-joint arm's closed form in f32: the f32 `fk` of every exact solution meets the f32
/// pose within `EXACT_TOLERANCE_F32`, and the generating configuration comes back within
/// 1e-4 rad for all but the configurations near a singularity (at most 1 %, counted;
/// 2 000 configurations drawn in the limits, fixed seed).
#[test]
fn f32_widowx250_ik_meets_its_own_fk() {
    let robot = WidowX250F32;
    let mut rng = XorShift64::new(250);
    let cases = 2_000;
    let mut missed = 0;
    for _ in 0..cases {
        let q: [f32; 5] = core::array::from_fn(|i| {
            let [lo, hi] = WidowX250F32::LIMITS[i];
            lo + (hi - lo) * rng.next_f64() as f32
        });
        let pose = robot.fk(&q);
        let sols = robot.ik(&pose);
        for b in sols.exact() {
            let t = robot.fk(&b.q);
            let e = (0..3)
                .flat_map(|i| (0..4).map(move |j| (i, j)))
                .map(|(i, j)| f64::from((t[i][j] - pose[i][j]).abs()))
                .fold(0.0, f64::max);
            assert!(e <= EXACT_TOLERANCE_F32, "{q:?}: {:?} is {e:e} off", b.q);
        }
        let found = sols.exact().any(|b| {
            (0..5).all(|i| {
                let d = f64::from(b.q[i]) - f64::from(q[i]);
                (d - TAU * (d / TAU).round()).abs() <= 1e-4
            })
        });
        missed += usize::from(!found);
    }
    eprintln!("WidowX 250 f32: {missed} of {cases} not found within 1e-4 rad");
    assert!(missed * 100 <= cases, "{missed} of {cases} not found");
}
