//! Time per IK solve on the UR5 (hand-written DH test robot from `tests/common`), for
//! reachable targets (fk of random configurations) from random seeds, per method.
//! Comparison with the `k` crate is a separate task.

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen::adapters::{fk_isometry, jacobian_matrix};
use kinegen::ik::{solve, solve_nearest, IkMethod, IkOptions, IkTarget, MultiStart, XorShift64};
use kinegen::velocity::{dls_velocity, inverse_velocity, Damping, DEFAULT_TOLERANCE};
use nalgebra::SVector;
use std::f64::consts::PI;
use std::hint::black_box;

fn problems(n: usize) -> Vec<(IkTarget, [f64; 6])> {
    let robot = common::ur5();
    let mut rng = XorShift64::new(2024);
    (0..n)
        .map(|_| {
            let q = rng.configuration(&[[-PI, PI]; 6]);
            let seed = rng.configuration(&[[-PI, PI]; 6]);
            (IkTarget::Pose(fk_isometry(&robot, &q)), seed)
        })
        .collect()
}

fn bench_ik(c: &mut Criterion) {
    let robot = common::ur5();
    let set = problems(256);
    let mut group = c.benchmark_group("ur5_ik");
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
                black_box(solve(&robot, t, s, &opts).is_ok())
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
            black_box(solve_nearest(&robot, t, s, &IkOptions::default(), &multi).is_ok())
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
