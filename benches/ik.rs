//! Time per IK solve on the generated UR5 (`kinegen_robots::Ur5`), for reachable targets
//! (fk of random configurations within the limits) from random seeds: kinegen's methods,
//! and kinegen against the `k` crate's `JacobianIkSolver` on the very same targets, seeds,
//! tolerances, iteration cap and joint limits.
//!
//! Before timing, a one-off comparison prints success rates, mean iterations and the
//! time-per-solve ratio, and checks that the `k` chain (built from the same DH table)
//! has the same forward kinematics as the generated code.
//!
//! Run: `cargo bench --bench ik`.

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen::adapters::{fk_isometry, jacobian_matrix};
use kinegen::ik::{solve, solve_nearest, IkMethod, IkOptions, IkTarget, MultiStart, XorShift64};
use kinegen::velocity::{dls_velocity, inverse_velocity, Damping, DEFAULT_TOLERANCE};
use kinegen::Kinematics;
use kinegen_robots::Ur5;
use nalgebra::SVector;
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// UR5 standard DH table, as in `robots/ur5.toml`: `(d, a, α)` per joint.
const UR5_DH: [(f64, f64, f64); 6] = [
    (0.089159, 0.0, FRAC_PI_2),
    (0.0, -0.425, 0.0),
    (0.0, -0.39225, 0.0),
    (0.10915, 0.0, FRAC_PI_2),
    (0.09465, 0.0, -FRAC_PI_2),
    (0.0823, 0.0, 0.0),
];

/// Tolerance both solvers must meet (k's default is 1 mm / 5 mrad; ours 1e-9).
const TOL: f64 = 1e-6;
/// Iteration cap of both solvers.
const MAX_ITERATIONS: usize = 100;

/// The UR5 as a `k` chain. Standard DH link `i` is `Rz(θᵢ) Tz(dᵢ) Tx(aᵢ) Rx(αᵢ)`, and
/// `Rz(θ)` commutes with `Tz(d)`, so the product regroups as
/// `Tz(d₁) Rz(θ₁) · [Tx(a₁) Rx(α₁) Tz(d₂)] Rz(θ₂) ⋯ Rz(θ₆) · [Tx(a₆) Rx(α₆)]`: node `i`'s
/// fixed origin is the previous link's `Tx Rx` followed by `Tz(dᵢ)`, its joint turns
/// about z, and the last link's `Tx Rx` is a fixed end node.
fn k_ur5(limits: &[[f64; 2]; 6]) -> k::SerialChain<f64> {
    use k::nalgebra as kna;
    let tx_rx = |a: f64, alpha: f64| {
        kna::Isometry3::from_parts(
            kna::Translation3::new(a, 0.0, 0.0),
            kna::UnitQuaternion::from_axis_angle(&kna::Vector3::x_axis(), alpha),
        )
    };
    let tz = |d: f64| kna::Isometry3::translation(0.0, 0.0, d);
    let mut nodes = Vec::new();
    let mut previous = kna::Isometry3::identity();
    for (i, &(d, a, alpha)) in UR5_DH.iter().enumerate() {
        let node: k::Node<f64> = k::NodeBuilder::new()
            .name(&format!("joint{}", i + 1))
            .origin(previous * tz(d))
            .joint_type(k::JointType::Rotational {
                axis: kna::Vector3::z_axis(),
            })
            .limits(Some(k::joint::Range::new(limits[i][0], limits[i][1])))
            .into_node();
        nodes.push(node);
        previous = tx_rx(a, alpha);
    }
    let end: k::Node<f64> = k::NodeBuilder::new()
        .name("tool")
        .origin(previous)
        .joint_type(k::JointType::Fixed)
        .into_node();
    nodes.push(end);
    for w in nodes.windows(2) {
        w[1].set_parent(&w[0]);
    }
    k::SerialChain::new_unchecked(k::Chain::from_root(nodes[0].clone()))
}

fn k_target(t: &nalgebra::Isometry3<f64>) -> k::nalgebra::Isometry3<f64> {
    let v = t.translation.vector;
    let q = t.rotation.coords;
    k::nalgebra::Isometry3::from_parts(
        k::nalgebra::Translation3::new(v.x, v.y, v.z),
        k::nalgebra::UnitQuaternion::new_normalize(k::nalgebra::Quaternion::new(
            q.w, q.x, q.y, q.z,
        )),
    )
}

/// Reachable targets (fk of random configurations) and independent random seeds.
fn problems(n: usize) -> Vec<(nalgebra::Isometry3<f64>, [f64; 6])> {
    let robot = Ur5::default();
    let limits = robot.limits();
    let mut rng = XorShift64::new(2024);
    (0..n)
        .map(|_| {
            let q = rng.configuration(&limits);
            let seed = rng.configuration(&limits);
            (fk_isometry(&robot, &q), seed)
        })
        .collect()
}

fn kinegen_options() -> IkOptions {
    IkOptions {
        position_tolerance: TOL,
        orientation_tolerance: TOL,
        max_iterations: MAX_ITERATIONS,
        ..IkOptions::default()
    }
}

fn k_solver(multiplier: f64) -> k::JacobianIkSolver<f64> {
    k::JacobianIkSolver::new(TOL, TOL, multiplier, MAX_ITERATIONS)
}

fn k_solve(
    chain: &k::SerialChain<f64>,
    solver: &k::JacobianIkSolver<f64>,
    target: &k::nalgebra::Isometry3<f64>,
    seed: &[f64; 6],
) -> bool {
    use k::InverseKinematicsSolver;
    chain.set_joint_positions_clamped(seed);
    solver.solve(chain, target).is_ok()
}

/// `k` does not report its iteration count, but it is deterministic from a seed and
/// checks convergence after every iteration, so the count is the smallest `num_max_try`
/// that succeeds: found by bisection.
fn k_iterations(
    chain: &k::SerialChain<f64>,
    multiplier: f64,
    target: &k::nalgebra::Isometry3<f64>,
    seed: &[f64; 6],
) -> Option<usize> {
    let with = |n: usize| {
        k_solve(
            chain,
            &k::JacobianIkSolver::new(TOL, TOL, multiplier, n),
            target,
            seed,
        )
    };
    if !with(MAX_ITERATIONS) {
        return None;
    }
    let (mut lo, mut hi) = (0, MAX_ITERATIONS); // fails at lo (0 tries never succeed), succeeds at hi
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if with(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// The k chain's FK equals the generated code's (else the comparison is meaningless).
fn check_same_fk(chain: &k::SerialChain<f64>) {
    let robot = Ur5::default();
    let mut rng = XorShift64::new(99);
    for _ in 0..100 {
        let q = rng.configuration(&robot.limits());
        chain.set_joint_positions_clamped(&q);
        let theirs = chain.end_transform();
        let ours = k_target(&fk_isometry(&robot, &q));
        let dp = (theirs.translation.vector - ours.translation.vector).norm();
        let da = theirs.rotation.angle_to(&ours.rotation);
        assert!(
            dp < 1e-12 && da < 1e-12,
            "k chain FK differs at {q:?}: {dp} m, {da} rad"
        );
    }
}

fn compare_once(set: &[(nalgebra::Isometry3<f64>, [f64; 6])]) {
    let robot = Ur5::default();
    let chain = k_ur5(&robot.limits());
    check_same_fk(&chain);
    let opts = kinegen_options();
    let targets: Vec<_> = set.iter().map(|(t, _)| k_target(t)).collect();

    let (mut ok, mut iters) = (0, 0);
    let start = Instant::now();
    for (t, s) in set {
        if let Ok(sol) = solve(&robot, &IkTarget::Pose(*t), s, &opts) {
            ok += 1;
            iters += sol.iterations;
        }
    }
    let ours = start.elapsed().as_secs_f64() / set.len() as f64;
    println!(
        "kinegen Newton-Raphson (line search, limits): {ok}/{} solved ({:.1}%), mean iterations {:.1}, {:.1} µs/solve",
        set.len(),
        100.0 * ok as f64 / set.len() as f64,
        iters as f64 / ok.max(1) as f64,
        1e6 * ours
    );
    for multiplier in [0.5, 1.0] {
        let solver = k_solver(multiplier);
        let start = Instant::now();
        let mut ok = 0;
        for (t, (_, s)) in targets.iter().zip(set) {
            ok += k_solve(&chain, &solver, t, s) as usize;
        }
        let theirs = start.elapsed().as_secs_f64() / set.len() as f64;
        let its: Vec<usize> = targets
            .iter()
            .zip(set)
            .filter_map(|(t, (_, s))| k_iterations(&chain, multiplier, t, s))
            .collect();
        println!(
            "k JacobianIkSolver (multiplier {multiplier}): {ok}/{} solved ({:.1}%), mean iterations {:.1}, {:.1} µs/solve; time ratio k / kinegen = {:.2}",
            set.len(),
            100.0 * ok as f64 / set.len() as f64,
            its.iter().sum::<usize>() as f64 / its.len().max(1) as f64,
            1e6 * theirs,
            theirs / ours
        );
        // Failures run to the iteration cap and dominate the means above; on the problems
        // both solvers solve, the ratio compares converging solves only.
        let both: Vec<usize> = (0..set.len())
            .filter(|&n| {
                solve(&robot, &IkTarget::Pose(set[n].0), &set[n].1, &opts).is_ok()
                    && k_solve(&chain, &solver, &targets[n], &set[n].1)
            })
            .collect();
        let reps = 20;
        let start = Instant::now();
        for _ in 0..reps {
            for &n in &both {
                black_box(solve(&robot, &IkTarget::Pose(set[n].0), &set[n].1, &opts).is_ok());
            }
        }
        let ours_both = start.elapsed().as_secs_f64();
        let start = Instant::now();
        for _ in 0..reps {
            for &n in &both {
                black_box(k_solve(&chain, &solver, &targets[n], &set[n].1));
            }
        }
        let theirs_both = start.elapsed().as_secs_f64();
        let per = |s: f64| 1e6 * s / (reps * both.len().max(1)) as f64;
        println!(
            "  on the {} problems both solve: kinegen {:.1} µs/solve, k {:.1} µs/solve, ratio k / kinegen = {:.2}",
            both.len(),
            per(ours_both),
            per(theirs_both),
            theirs_both / ours_both
        );
    }
}

fn bench_ik(c: &mut Criterion) {
    let robot = Ur5::default();
    let set = problems(256);
    compare_once(&set);

    let mut group = c.benchmark_group("ur5_ik_vs_k");
    group.measurement_time(Duration::from_secs(5));
    let opts = kinegen_options();
    let mut i = 0;
    group.bench_function("kinegen_newton_raphson", |b| {
        b.iter(|| {
            let (t, s) = &set[i % set.len()];
            i += 1;
            black_box(solve(&robot, &IkTarget::Pose(*t), s, &opts).is_ok())
        })
    });
    let chain = k_ur5(&robot.limits());
    let targets: Vec<_> = set.iter().map(|(t, _)| k_target(t)).collect();
    for multiplier in [0.5, 1.0] {
        let solver = k_solver(multiplier);
        let mut i = 0;
        group.bench_function(format!("k_jacobian_multiplier_{multiplier}"), |b| {
            b.iter(|| {
                let n = i % set.len();
                i += 1;
                black_box(k_solve(&chain, &solver, &targets[n], &set[n].1))
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group("ur5_ik");
    group.measurement_time(Duration::from_secs(3));
    for (name, opts) in [
        ("newton_raphson", IkOptions::default()),
        (
            "dls",
            IkOptions {
                method: IkMethod::DampedLeastSquares(Damping::default()),
                ..IkOptions::default()
            },
        ),
        (
            "levenberg_marquardt",
            IkOptions {
                method: IkMethod::LevenbergMarquardt { initial_mu: 1e-2 },
                ..IkOptions::default()
            },
        ),
    ] {
        let mut i = 0;
        group.bench_function(format!("{name}_single_start"), |b| {
            b.iter(|| {
                let (t, s) = &set[i % set.len()];
                i += 1;
                black_box(solve(&robot, &IkTarget::Pose(*t), s, &opts).is_ok())
            })
        });
    }
    let multi = MultiStart {
        starts: 20,
        rng_seed: 5,
        stop_at_first: true,
    };
    let mut i = 0;
    group.bench_function("newton_raphson_multi_start_20", |b| {
        b.iter(|| {
            let (t, s) = &set[i % set.len()];
            i += 1;
            black_box(
                solve_nearest(
                    &robot,
                    &IkTarget::Pose(*t),
                    s,
                    &IkOptions::default(),
                    &multi,
                )
                .is_ok(),
            )
        })
    });
    group.finish();

    let q = [0.3, -1.1, 1.2, -0.4, 0.9, 0.2];
    let j = jacobian_matrix(&robot, &q);
    let xdot = SVector::<f64, 6>::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
    c.bench_function("inverse_velocity_lu_6x6", |b| {
        b.iter(|| inverse_velocity(black_box(&j), &xdot, DEFAULT_TOLERANCE))
    });
    c.bench_function("dls_velocity_svd_6x6", |b| {
        b.iter(|| dls_velocity(black_box(&j), &xdot, &Damping::default()))
    });
}

criterion_group!(benches, bench_ik);
criterion_main!(benches);
