//! The KUKA iiwa by its arm angle (`ik_arm_angle`, `arm_angle`, `arm_angle_intervals`):
//!
//! - for 1 000 poses (fk of configurations drawn within the limits, fixed seed) × 50 arm
//!   angles, every exact configuration returned reproduces the pose (max entry error
//!   ≤ 1e-10, the arm's reach being 1.3 m) and has the arm angle it was asked for, one per
//!   global configuration; at the generating configuration's own arm angle it is among
//!   them;
//! - the intervals: ψ just inside an interval's end gives the configuration within the
//!   limits, just outside a joint over its limit — at both ends, for every configuration of
//!   200 poses;
//! - an f32 iiwa's arm-angle methods: the f64 iiwa's (with the f32 parameters widened) on
//!   the same widened pose and ψ, rounded to f32 — solutions and flags, the arm angle, the
//!   intervals (with the f32 robot's limits).

use core::f64::consts::{PI, TAU};
use kinegen::ik::families::configuration;
use kinegen::ik::XorShift64;
use kinegen_robots::KukaIiwa14;

kinegen::kinematics! {
    /// The iiwa in single precision.
    pub struct KukaIiwa14F32 = "robots/kuka_iiwa14.toml";
    scalar: f32,
}

fn pose_error(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> f64 {
    let mut e: f64 = 0.0;
    for i in 0..3 {
        for j in 0..4 {
            e = e.max((a[i][j] - b[i][j]).abs());
        }
    }
    e
}

fn wrap(x: f64) -> f64 {
    x - TAU * (x / TAU).round()
}

fn random_q(rng: &mut XorShift64) -> [f64; 7] {
    core::array::from_fn(|i| {
        let [lo, hi] = KukaIiwa14::LIMITS[i];
        lo + (hi - lo) * rng.next_f64()
    })
}

#[test]
fn every_solution_has_the_arm_angle_asked_for() {
    let robot = KukaIiwa14::default();
    let mut rng = XorShift64::new(0x5125);
    let (mut solutions, mut undefined) = (0usize, 0usize);
    for _ in 0..1_000 {
        let q = random_q(&mut rng);
        let pose = robot.fk(&q);
        let Some(own) = robot.arm_angle(&q) else {
            undefined += 1;
            continue;
        };
        let at_own = robot.ik_arm_angle(&pose, own);
        assert!(
            at_own
                .exact()
                .any(|b| (0..7).all(|i| wrap(b.q[i] - q[i]).abs() < 1e-8)),
            "q = {q:?} is not among its arm angle's solutions {:?}",
            at_own.as_slice()
        );
        for k in 0..50 {
            let psi = -PI + TAU * (k as f64 + 0.5) / 50.0;
            let sols = robot.ik_arm_angle(&pose, psi);
            let mut configs = Vec::new();
            for b in sols.exact() {
                let e = pose_error(&robot.fk(&b.q), &pose);
                assert!(e <= 1e-10, "ψ = {psi}: {:?} is {e:e} off", b.q);
                if let Some(a) = robot.arm_angle(&b.q) {
                    assert!(
                        wrap(a - psi).abs() < 1e-9,
                        "ψ = {psi}: {:?} has arm angle {a}",
                        b.q
                    );
                }
                let c = configuration(&b.q);
                assert!(
                    !configs.contains(&c),
                    "two solutions of configuration {c:?}"
                );
                configs.push(c);
                solutions += 1;
            }
        }
    }
    eprintln!(
        "{solutions} exact solutions over 50 000 (pose, ψ); {undefined} poses without an arm angle"
    );
    assert!(solutions > 100_000, "most (pose, ψ) have several solutions");
}

#[test]
fn the_intervals_end_where_a_joint_meets_its_limit() {
    let robot = KukaIiwa14::default();
    let mut rng = XorShift64::new(0x1a7e);
    let mut ends = 0;
    for _ in 0..200 {
        let q = random_q(&mut rng);
        let pose = robot.fk(&q);
        for c in 0..8 {
            let config = [c & 4 != 0, c & 2 != 0, c & 1 != 0];
            let ok = |psi: f64| {
                robot
                    .ik_arm_angle(&pose, psi)
                    .exact()
                    .any(|b| configuration(&b.q) == config && b.within_limits)
            };
            let iv = robot.arm_angle_intervals(&pose, config);
            for &[lo, hi] in iv.as_slice() {
                assert!(lo <= hi);
                assert!(ok(0.5 * (lo + hi)), "{config:?} [{lo}, {hi}] of q = {q:?}");
                for (end, inside) in [(lo, lo + 1e-7), (hi, hi - 1e-7)] {
                    if end.abs() < PI {
                        let outside = 2.0 * end - inside;
                        assert!(
                            ok(inside) && !ok(outside),
                            "{config:?} end {end} of [{lo}, {hi}] for q = {q:?}"
                        );
                        ends += 1;
                    }
                }
            }
        }
        // The generating configuration lies in its own configuration's intervals.
        if let Some(own) = robot.arm_angle(&q) {
            let iv = robot.arm_angle_intervals(&pose, configuration(&q));
            assert!(
                iv.contains(own),
                "q = {q:?} at ψ = {own} not in {:?}",
                iv.as_slice()
            );
        }
    }
    eprintln!("{ends} interval ends checked");
    assert!(ends > 100);
}

#[test]
fn f32_arm_angle_is_the_f64_one_rounded() {
    let r32 = KukaIiwa14F32::default();
    let r64 = KukaIiwa14 {
        d1: f64::from(r32.d1),
        d3: f64::from(r32.d3),
        d5: f64::from(r32.d5),
        d7: f64::from(r32.d7),
    };
    let mut rng = XorShift64::new(0xf32);
    let mut solutions = 0;
    for _ in 0..500 {
        let q = random_q(&mut rng).map(|x| x as f32);
        let pose32 = r32.fk(&q);
        let pose = pose32.map(|r| r.map(f64::from));
        // What the f32 robot solves: its pose widened and made orthonormal.
        let target = kinegen::ik::solutions::pose_matrix(&kinegen::ik::solutions::orthonormalized(
            &kinegen::ik::geometry::Pose::from_matrix(&pose),
        ));
        let psi32 = r32.arm_angle(&q).unwrap_or(0.3);
        let psi = f64::from(psi32);
        assert_eq!(
            r32.arm_angle(&q),
            r64.arm_angle(&q.map(f64::from)).map(|x| x as f32)
        );
        let (a, b) = (
            r32.ik_arm_angle(&pose32, psi32),
            r64.ik_arm_angle(&target, psi),
        );
        assert_eq!(a.len(), b.len(), "{q:?}");
        for (x, y) in a.iter().zip(b.iter()) {
            assert_eq!(x.q, y.q.map(|v| v as f32), "{q:?}");
            // (`within_limits` is judged against each robot's own limits, the f32 ones
            // rounded: not compared.)
            assert_eq!((x.exact, x.singular), (y.exact, y.singular), "{q:?}");
        }
        solutions += a.len();
        // The f32 robot's limits are its own (rounded to f32), widened.
        let limits = KukaIiwa14F32::LIMITS.map(|l| l.map(f64::from));
        for config in [[true, true, true], [false, true, false]] {
            let own = kinegen::ik::families::arm_angle_intervals(
                &r64.ik_geometry(),
                &kinegen::ik::geometry::Pose::from_matrix(&target),
                config,
                &limits,
            );
            assert_eq!(
                r32.arm_angle_intervals(&pose32, config).as_slice(),
                own.as_slice()
            );
        }
    }
    assert!(solutions >= 500, "{solutions}");
}
