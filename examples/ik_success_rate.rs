//! Measures numerical IK on the generated UR5 and Panda (`kinegen-robots`): success rate
//! on reachable random targets (fk of random configurations within the joint limits) from
//! random seeds, iterations, residuals and time per solve, single- and multi-start.
//!
//! Run: `cargo run --release --example ik_success_rate [targets]` (default 10 000).
//! `tests/runtime_ik.rs` runs the same measurement on fewer targets in CI.

use kinegen::adapters::{fk_isometry, rotation_of, translation_of};
use kinegen::ik::{solve, solve_nearest, IkMethod, IkOptions, IkTarget, MultiStart, XorShift64};
use kinegen::Kinematics;
use kinegen_robots::{Panda, Ur5};
use std::time::Instant;

struct Row {
    solved: usize,
    total: usize,
    iterations: usize,
    attempts: usize,
    worst_position: f64,
    worst_angle: f64,
    seconds: f64,
}

fn measure<R: Kinematics<N>, const N: usize>(
    robot: &R,
    options: &IkOptions,
    multi: Option<MultiStart>,
    targets: usize,
) -> Row {
    let limits = robot.limits();
    let mut target_rng = XorShift64::new(2024);
    let mut seed_rng = XorShift64::new(77);
    let problems: Vec<_> = (0..targets)
        .map(|_| {
            let q = target_rng.configuration(&limits);
            (fk_isometry(robot, &q), seed_rng.configuration(&limits))
        })
        .collect();
    let mut row = Row {
        solved: 0,
        total: targets,
        iterations: 0,
        attempts: 0,
        worst_position: 0.0,
        worst_angle: 0.0,
        seconds: 0.0,
    };
    let start = Instant::now();
    let results: Vec<_> = problems
        .iter()
        .map(|(target, seed)| {
            let t = IkTarget::Pose(*target);
            match multi {
                None => solve(robot, &t, seed, options),
                Some(m) => solve_nearest(robot, &t, seed, options, &m),
            }
        })
        .collect();
    row.seconds = start.elapsed().as_secs_f64();
    for ((target, _), result) in problems.iter().zip(results) {
        if let Ok(sol) = result {
            let t = robot.fk(&sol.q);
            let dp = (translation_of(&t) - target.translation.vector).norm();
            let diff = (rotation_of(&t) - target.rotation.to_rotation_matrix().into_inner()).norm();
            let angle = 2.0 * (diff / (2.0 * 2f64.sqrt())).min(1.0).asin();
            row.solved += 1;
            row.iterations += sol.iterations;
            row.attempts += sol.attempts;
            row.worst_position = row.worst_position.max(dp);
            row.worst_angle = row.worst_angle.max(angle);
        }
    }
    row
}

fn report<R: Kinematics<N>, const N: usize>(robot: &R, targets: usize) {
    let nr = IkOptions::default();
    let lm = IkOptions {
        method: IkMethod::LevenbergMarquardt { initial_mu: 1e-2 },
        ..IkOptions::default()
    };
    let multi = |starts| MultiStart {
        starts,
        rng_seed: 5,
        stop_at_first: true,
    };
    for (name, opts, m) in [
        ("Newton-Raphson, 1 start", nr, None),
        ("Levenberg-Marquardt, 1 start", lm, None),
        ("Newton-Raphson, up to 20 starts", nr, Some(multi(20))),
        ("Levenberg-Marquardt, up to 20 starts", lm, Some(multi(20))),
    ] {
        let r = measure(robot, &opts, m, targets);
        println!(
            "{:<12} {:<38} {:>6}/{} = {:6.2}%  iterations {:5.1}  starts {:4.2}  worst residual {:.1e} m {:.1e} rad  {:7.1} µs/target",
            R::NAME,
            name,
            r.solved,
            r.total,
            100.0 * r.solved as f64 / r.total as f64,
            r.iterations as f64 / r.solved.max(1) as f64,
            r.attempts as f64 / r.solved.max(1) as f64,
            r.worst_position,
            r.worst_angle,
            1e6 * r.seconds / r.total as f64,
        );
    }
}

fn main() {
    let targets = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    report(&Ur5::default(), targets);
    report(&Panda::default(), targets);
}
