//! Numerical IK: success rate on reachable UR5 targets, residuals, limits, reasons for
//! failure, multi-start.

mod common;

use common::*;
use kinegen::adapters::{fk_isometry, rotation_of, translation_of};
use kinegen::ik::*;
use kinegen::pose_error::{orientation_error, rotation_vector};
use kinegen::velocity::Damping;
use kinegen::Kinematics;
use nalgebra::{Isometry3, Matrix3, Rotation3, Vector3};
use std::f64::consts::PI;

/// Independent residual check: position and rotation angle between fk(q) and the target.
fn pose_residual<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    target: &Isometry3<f64>,
) -> (f64, f64) {
    let t = robot.fk(q);
    let dp = (translation_of(&t) - target.translation.vector).norm();
    // ‖R − R_d‖_F = 2√2 sin(θ/2): accurate for small θ, unlike acos of the trace.
    let diff = (rotation_of(&t) - target.rotation.to_rotation_matrix().into_inner()).norm();
    let angle = 2.0 * (diff / (2.0 * 2f64.sqrt())).min(1.0).asin();
    (dp, angle)
}

fn within_limits<const N: usize>(q: &[f64; N], limits: &[[f64; 2]; N]) -> bool {
    (0..N).all(|i| q[i] >= limits[i][0] && q[i] <= limits[i][1])
}

struct Stats {
    name: &'static str,
    solved: usize,
    total: usize,
    iterations: usize,
    attempts: usize,
    worst_position: f64,
    worst_angle: f64,
}

impl Stats {
    fn rate(&self) -> f64 {
        100.0 * self.solved as f64 / self.total as f64
    }
    fn print(&self) {
        println!(
            "UR5 IK {:<44} {:>5}/{} = {:6.2}%  mean iterations {:5.1}  mean attempts {:4.2}  worst residual {:.1e} m {:.1e} rad",
            self.name,
            self.solved,
            self.total,
            self.rate(),
            self.iterations as f64 / self.solved.max(1) as f64,
            self.attempts as f64 / self.solved.max(1) as f64,
            self.worst_position,
            self.worst_angle
        );
    }
}

/// Targets are fk of random configurations (so reachable); seeds are independent random
/// configurations. Deterministic: the same xorshift streams every run.
fn run_success_rate(
    name: &'static str,
    options: &IkOptions,
    multi: Option<MultiStart>,
    targets: usize,
) -> Stats {
    let robot = ur5();
    let limits = robot.limits();
    let sample = [[-PI, PI]; 6];
    let mut target_rng = XorShift64::new(2024);
    let mut seed_rng = XorShift64::new(77);
    let mut stats = Stats {
        name,
        solved: 0,
        total: targets,
        iterations: 0,
        attempts: 0,
        worst_position: 0.0,
        worst_angle: 0.0,
    };
    for _ in 0..targets {
        let q_true = target_rng.configuration(&sample);
        let target = fk_isometry(&robot, &q_true);
        let seed = seed_rng.configuration(&sample);
        let result = match multi {
            None => solve(&robot, &IkTarget::Pose(target), &seed, options),
            Some(m) => solve_nearest(&robot, &IkTarget::Pose(target), &seed, options, &m),
        };
        if let Ok(sol) = result {
            let (dp, angle) = pose_residual(&robot, &sol.q, &target);
            assert!(
                dp <= 1.01 * options.position_tolerance
                    && angle <= 1.01 * options.orientation_tolerance,
                "reported converged but residual {dp} m, {angle} rad"
            );
            assert!(within_limits(&sol.q, &limits));
            stats.solved += 1;
            stats.iterations += sol.iterations;
            stats.attempts += sol.attempts;
            stats.worst_position = stats.worst_position.max(dp);
            stats.worst_angle = stats.worst_angle.max(angle);
        }
    }
    stats.print();
    stats
}

/// ≥ 99.5% of 400 reachable targets from random seeds on the hand-written UR5 of
/// `common` (an independent implementation of the same DH table; the generated robots
/// are measured in `generated_ur5_and_panda_success_rate`). Multi-start restarts from
/// further pseudo-random seeds when a start fails (stopping at the first success);
/// single-start rates are printed alongside for comparison.
#[test]
fn ur5_success_rate_from_random_seeds() {
    let targets = 400;
    let nr = IkOptions::default();
    let lm = IkOptions {
        method: IkMethod::LevenbergMarquardt { initial_mu: 1e-2 },
        ..IkOptions::default()
    };
    run_success_rate("Newton-Raphson, 1 start", &nr, None, targets);
    run_success_rate("Levenberg-Marquardt, 1 start", &lm, None, targets);
    let multi_nr = run_success_rate(
        "Newton-Raphson, up to 20 starts",
        &nr,
        Some(MultiStart {
            starts: 20,
            rng_seed: 5,
            stop_at_first: true,
        }),
        targets,
    );
    let multi_lm = run_success_rate(
        "Levenberg-Marquardt, up to 10 starts",
        &lm,
        Some(MultiStart {
            starts: 10,
            rng_seed: 5,
            stop_at_first: true,
        }),
        targets,
    );
    assert!(
        multi_nr.rate() >= 99.5,
        "NR multi-start success {:.2}% < 99.5%",
        multi_nr.rate()
    );
    assert!(
        multi_lm.rate() >= 99.5,
        "LM multi-start success {:.2}% < 99.5%",
        multi_lm.rate()
    );
}

/// The acceptance measurement on the *generated* robots of `kinegen-robots`: UR5 (6×6 J)
/// and the redundant Panda (6×7 J, tight real joint limits). Targets are fk of random
/// configurations within the limits, seeds random within the limits. 400 targets per
/// robot keep the debug-build run short; `examples/ik_success_rate.rs` runs the same
/// measurement on 10 000 (release).
#[test]
fn generated_ur5_and_panda_success_rate() {
    fn run<R: Kinematics<N>, const N: usize>(robot: &R, targets: usize) {
        let limits = robot.limits();
        let mut target_rng = XorShift64::new(2024);
        let mut seed_rng = XorShift64::new(77);
        let opts = IkOptions::default();
        let multi = MultiStart {
            starts: 20,
            rng_seed: 5,
            stop_at_first: true,
        };
        let (mut single, mut solved, mut iterations, mut attempts) = (0, 0, 0, 0);
        let (mut worst_p, mut worst_a) = (0.0f64, 0.0f64);
        for _ in 0..targets {
            let q_true = target_rng.configuration(&limits);
            let target = fk_isometry(robot, &q_true);
            let seed = seed_rng.configuration(&limits);
            let t = IkTarget::Pose(target);
            single += solve(robot, &t, &seed, &opts).is_ok() as usize;
            match solve_nearest(robot, &t, &seed, &opts, &multi) {
                Ok(sol) => {
                    let (dp, angle) = pose_residual(robot, &sol.q, &target);
                    assert!(
                        dp <= 1.01 * opts.position_tolerance
                            && angle <= 1.01 * opts.orientation_tolerance,
                        "{}: reported converged but residual {dp} m, {angle} rad",
                        R::NAME
                    );
                    assert!(within_limits(&sol.q, &limits), "{:?}", sol.q);
                    solved += 1;
                    iterations += sol.iterations;
                    attempts += sol.attempts;
                    worst_p = worst_p.max(dp);
                    worst_a = worst_a.max(angle);
                }
                Err(e) => {
                    // A failure must still be a clean error with a finite residual.
                    if let IkError::NotConverged { residual, q, .. } = e {
                        assert!(residual.is_finite() && within_limits(&q, &limits));
                    }
                }
            }
        }
        let rate = 100.0 * solved as f64 / targets as f64;
        println!(
            "{} (generated): 1 start {single}/{targets}; up to 20 starts {solved}/{targets} = {rate:.2}%, mean iterations {:.1}, mean starts {:.2}, worst residual {worst_p:.1e} m {worst_a:.1e} rad",
            R::NAME,
            iterations as f64 / solved.max(1) as f64,
            attempts as f64 / solved.max(1) as f64,
        );
        assert!(rate >= 99.5, "{}: success {rate:.2}% < 99.5%", R::NAME);
    }
    run(&kinegen_robots::Ur5::default(), 400);
    run(&kinegen_robots::Panda::default(), 400);
}

/// Revolute joints with a full turn of range (UR's ±2π) are wrapped, not clamped: a
/// solve that would cross +2π comes back inside the range with the same pose.
#[test]
fn full_turn_joints_wrap_instead_of_sticking_at_the_limit() {
    let robot = kinegen_robots::Ur5::default();
    let tau = 2.0 * PI;
    let q_true = [0.4, -1.2, 1.3, -0.5, 1.1, 0.3];
    let target = fk_isometry(&robot, &q_true);
    // Joint 1 starts just below +2π; the solution at 0.4 + 2π is out of range, so the
    // solver must get to 0.4 (or another equivalent) through the wrap.
    let mut seed = q_true;
    seed[0] = tau - 0.05;
    let sol = solve(
        &robot,
        &IkTarget::Pose(target),
        &seed,
        &IkOptions::default(),
    )
    .unwrap();
    assert!(within_limits(&sol.q, &robot.limits()));
    let (dp, angle) = pose_residual(&robot, &sol.q, &target);
    assert!(dp <= 1e-9 && angle <= 1e-9);
    // A seed far outside the range (many turns) is wrapped in, not rejected or clamped.
    let mut far = q_true;
    far[5] += 40.0 * tau;
    let sol = solve(&robot, &IkTarget::Pose(target), &far, &IkOptions::default()).unwrap();
    assert!(within_limits(&sol.q, &robot.limits()));
    assert!(
        (sol.q[5] - q_true[5])
            .rem_euclid(tau)
            .min((q_true[5] - sol.q[5]).rem_euclid(tau))
            < 1e-6
    );
}

#[test]
fn position_only_targets_on_redundant_and_planar_arms() {
    let mut rng = XorShift64::new(9);
    let r7 = redundant7();
    let opts = IkOptions::default();
    let (mut single, mut multi) = (0, 0);
    let starts = MultiStart {
        starts: 10,
        rng_seed: 2,
        stop_at_first: true,
    };
    for _ in 0..100 {
        let q_true = rng.configuration(&r7.limits());
        let p = translation_of(&r7.fk(&q_true));
        let seed = rng.configuration(&r7.limits());
        if solve(&r7, &IkTarget::Position(p), &seed, &opts).is_ok() {
            single += 1;
        }
        if let Ok(sol) = solve_nearest(&r7, &IkTarget::Position(p), &seed, &opts, &starts) {
            assert!((translation_of(&r7.fk(&sol.q)) - p).norm() <= 1e-9);
            assert_eq!(sol.orientation_error, 0.0);
            multi += 1;
        }
    }
    // Single starts fail when a joint ends on its ±6 rad limit (a local minimum of the
    // clamped problem); restarts get around that.
    println!("7-joint arm, position only: 1 start {single}/100, up to 10 starts {multi}/100");
    assert!(multi >= 99, "{multi}/100");
    // Planar RRR: position rows vx, vy, vz (vz is identically zero: rank 2 of 3 rows).
    let rrr = planar_rrr();
    let target = Vector3::new(4.0, 3.0, 0.0);
    let sol = solve(&rrr, &IkTarget::Position(target), &[0.1, 0.2, 0.3], &opts).unwrap();
    assert!((translation_of(&rrr.fk(&sol.q)) - target).norm() <= 1e-9);
}

#[test]
fn jacobian_transpose_and_dls_converge_on_planar_rr() {
    let rr = planar_rr();
    let target = IkTarget::Position(Vector3::new(0.9, 0.9, 0.0));
    for method in [
        IkMethod::JacobianTranspose,
        IkMethod::DampedLeastSquares(Damping::default()),
        IkMethod::LevenbergMarquardt { initial_mu: 1.0 },
    ] {
        let opts = IkOptions {
            method,
            max_iterations: 5000,
            position_tolerance: 1e-8,
            ..IkOptions::default()
        };
        let sol =
            solve(&rr, &target, &[0.3, 1.0], &opts).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        assert!((translation_of(&rr.fk(&sol.q)) - Vector3::new(0.9, 0.9, 0.0)).norm() <= 1e-8);
        println!("planar RR {method:?}: {} iterations", sol.iterations);
    }
}

#[test]
fn joint_limits_are_respected() {
    let mut robot = ur5();
    robot.limits = [
        [-1.5, 1.5],
        [-2.5, 0.0],
        [-2.0, 2.0],
        [-1.0, 1.0],
        [-1.5, 1.5],
        [-1.0, 1.0],
    ];
    let mut rng = XorShift64::new(3);
    let mut solved = 0;
    for _ in 0..200 {
        let q_true = rng.configuration(&robot.limits);
        let target = fk_isometry(&robot, &q_true);
        let seed = rng.configuration(&robot.limits);
        match solve_nearest(
            &robot,
            &IkTarget::Pose(target),
            &seed,
            &IkOptions::default(),
            &MultiStart {
                starts: 10,
                rng_seed: 1,
                stop_at_first: true,
            },
        ) {
            Ok(sol) => {
                assert!(within_limits(&sol.q, &robot.limits), "{:?}", sol.q);
                solved += 1;
            }
            Err(IkError::NotConverged { q, .. }) => assert!(within_limits(&q, &robot.limits)),
            Err(e) => panic!("unexpected {e}"),
        }
    }
    println!("UR5 with tight limits, up to 10 starts: {solved}/200");
    assert!(solved >= 190, "{solved}/200");
}

#[test]
fn reasons_for_failure() {
    let robot = ur5();
    let seed = [0.1, -1.0, 1.0, 0.2, 0.5, 0.0];
    let opts = IkOptions::default();
    // Out of reach: 2 m away, the UR5 reaches < 1 m.
    let (centre, reach) = reach_bound(&robot, &seed).unwrap();
    let far = IkTarget::Position(centre + Vector3::new(2.0, 0.0, 0.0));
    match solve(&robot, &far, &seed, &opts) {
        Err(IkError::OutOfReach { distance, reach: r }) => {
            assert!(distance > r && (r - reach).abs() < 1e-12)
        }
        other => panic!("{other:?}"),
    }
    // The reach sphere contains every configuration's tool point.
    let mut rng = XorShift64::new(11);
    let mut max_seen: f64 = 0.0;
    for _ in 0..2000 {
        let q = rng.configuration(&[[-PI, PI]; 6]);
        max_seen = max_seen.max((translation_of(&robot.fk(&q)) - centre).norm());
    }
    assert!(max_seen <= reach, "{max_seen} > {reach}");
    println!(
        "UR5 reach bound {reach:.4} m, farthest of 2000 random configurations {max_seen:.4} m"
    );
    // Invalid input.
    let nan = IkTarget::Position(Vector3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        solve(&robot, &nan, &seed, &opts),
        Err(IkError::InvalidInput(_))
    ));
    let good = IkTarget::Pose(fk_isometry(&robot, &[0.5, -1.2, 1.1, 0.0, 1.0, 0.3]));
    assert!(matches!(
        solve(&robot, &good, &[f64::NAN; 6], &opts),
        Err(IkError::InvalidInput(_))
    ));
    let zero_tol = IkOptions {
        position_tolerance: 0.0,
        ..opts
    };
    assert!(matches!(
        solve(&robot, &good, &seed, &zero_tol),
        Err(IkError::InvalidInput(_))
    ));
    // Not converged: one iteration is not enough from a far seed.
    let one = IkOptions {
        max_iterations: 1,
        ..opts
    };
    match solve(&robot, &good, &[-2.0, -2.0, -2.0, 2.0, 2.0, 2.0], &one) {
        Err(IkError::NotConverged {
            iterations,
            residual,
            ..
        }) => assert!(iterations == 1 && residual > 1e-3),
        other => panic!("{other:?}"),
    }
    // Singular: planar RR stretched out along x, asked to move along x (J's x row is 0).
    let rr = planar_rr();
    match solve(
        &rr,
        &IkTarget::Position(Vector3::new(1.5, 0.0, 0.0)),
        &[0.0, 0.0],
        &opts,
    ) {
        Err(IkError::Singular { sigma_min, q }) => {
            assert!(sigma_min < 1e-12);
            assert_eq!(q, [0.0, 0.0]);
        }
        other => panic!("{other:?}"),
    }
    // … which multi-start gets around.
    let sol = solve_nearest(
        &rr,
        &IkTarget::Position(Vector3::new(1.5, 0.0, 0.0)),
        &[0.0, 0.0],
        &opts,
        &MultiStart::default(),
    )
    .unwrap();
    assert!((translation_of(&rr.fk(&sol.q)) - Vector3::new(1.5, 0.0, 0.0)).norm() < 1e-9);
    assert!(IkError::<2>::InvalidInput("x")
        .to_string()
        .contains("invalid IK input"));
}

#[test]
fn multi_start_returns_the_solution_nearest_to_the_reference() {
    let robot = ur5();
    let mut rng = XorShift64::new(21);
    let multi = MultiStart {
        starts: 30,
        rng_seed: 4,
        stop_at_first: false,
    };
    for _ in 0..20 {
        let q_ref = rng.configuration(&[[-PI, PI]; 6]);
        let target = IkTarget::Pose(fk_isometry(&robot, &q_ref));
        // Start far from the reference: the nearest solution is still q_ref itself.
        let mut near = q_ref;
        near[0] += 0.05;
        near[4] -= 0.05;
        let best = solve_nearest(&robot, &target, &near, &IkOptions::default(), &multi).unwrap();
        let d = |q: &[f64; 6]| {
            q.iter()
                .zip(near.iter())
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
        };
        assert!(
            d(&best.q) <= d(&q_ref) + 1e-6,
            "{:?} farther than {:?}",
            best.q,
            q_ref
        );
        // Deterministic.
        assert_eq!(
            best,
            solve_nearest(&robot, &target, &near, &IkOptions::default(), &multi).unwrap()
        );
        assert_eq!(best.attempts, 30);
    }
}

#[test]
fn orientation_error_is_the_rotation_vector() {
    // Half a turn: the skew part of R vanishes, the rotation vector must not.
    let r = Rotation3::from_axis_angle(&Vector3::y_axis(), PI);
    let v = rotation_vector(r.matrix());
    assert!(
        (v.norm() - PI).abs() < 1e-12
            && (v.normalize().dot(&Vector3::y()).abs() - 1.0).abs() < 1e-12
    );
    let mut rng = XorShift64::new(5);
    for _ in 0..200 {
        let axis = Vector3::new(
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
        )
        .normalize();
        let angle = PI * rng.next_f64();
        let rc = Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(0.3, 0.1, -0.2)),
            0.7,
        );
        let rd = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle) * rc;
        let e = orientation_error(rd.matrix(), rc.matrix());
        assert!((e - axis * angle).norm() < 1e-9, "{e} vs {}", axis * angle);
    }
    assert_eq!(rotation_vector(&Matrix3::identity()), Vector3::zeros());
}
