//! The KUKA iiwa by its arm angle, on 1 000 poses (fk of configurations drawn within the
//! limits, fixed seed), each at the arm angle of the configuration that made it:
//!
//! - `ik_arm_angle`: all eight configurations at that arm angle (issue target ≤ 1 µs);
//! - `arm_angle_intervals`: the exact intervals of arm angle in which the generating
//!   configuration's global configuration keeps every joint inside the limits (target
//!   ≤ 3 µs; KIT's RLL solver: under 10 µs);
//! - `ik_with`: all solutions with joint 7 locked, for scale.
//!
//! A one-off check first: every exact solution reaches the pose (kinegen's fk, 1e-10),
//! and the generating configuration is among its arm angle's solutions and inside its
//! intervals. Run: `cargo bench --bench ik_arm_angle`.

use std::f64::consts::TAU;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen::ik::families::configuration;
use kinegen::ik::XorShift64;
use kinegen_robots::KukaIiwa14;

/// 1 000 poses when timing (`cargo bench`), 50 when CI runs the bench once as a test.
fn poses_count() -> usize {
    if std::env::args().any(|a| a == "--bench") {
        1000
    } else {
        50
    }
}

/// A pose, the configuration that made it and its arm angle.
type Case = ([[f64; 4]; 4], [f64; 7], f64);

fn cases(robot: &KukaIiwa14) -> Vec<Case> {
    let mut rng = XorShift64::new(2026);
    (0..poses_count())
        .map(|_| {
            let q: [f64; 7] = core::array::from_fn(|i| {
                let [lo, hi] = KukaIiwa14::LIMITS[i];
                lo + (hi - lo) * rng.next_f64()
            });
            let psi = robot.arm_angle(&q).expect("an arm angle");
            (robot.fk(&q), q, psi)
        })
        .collect()
}

fn check(robot: &KukaIiwa14, set: &[Case]) {
    let (mut solutions, mut found, mut inside) = (0, 0, 0);
    for (pose, q, psi) in set {
        let sols = robot.ik_arm_angle(pose, *psi);
        for b in sols.exact() {
            let t = robot.fk(&b.q);
            let e = (0..3)
                .flat_map(|r| (0..4).map(move |c| (r, c)))
                .map(|(r, c)| (t[r][c] - pose[r][c]).abs())
                .fold(0.0, f64::max);
            assert!(e <= 1e-10, "a solution {e:e} off");
            solutions += 1;
        }
        let same = |b: &[f64; 7]| {
            (0..7).all(|i| {
                let d = b[i] - q[i];
                (d - TAU * (d / TAU).round()).abs() < 1e-8
            })
        };
        found += usize::from(sols.exact().any(|b| same(&b.q)));
        let iv = robot.arm_angle_intervals(pose, configuration(q));
        inside += usize::from(iv.contains(*psi));
    }
    assert_eq!(
        found,
        set.len(),
        "the generating configuration at its arm angle"
    );
    assert_eq!(
        inside,
        set.len(),
        "the generating arm angle inside its intervals"
    );
    println!(
        "iiwa by arm angle: {solutions} exact solutions over {} poses; generating q found {found}, inside its intervals {inside}",
        set.len()
    );
}

fn bench(c: &mut Criterion) {
    let robot = KukaIiwa14::default();
    let set = cases(&robot);
    check(&robot, &set);
    let mut g = c.benchmark_group("iiwa_arm_angle_1000_poses");
    g.bench_function("ik_arm_angle", |b| {
        b.iter(|| {
            for (pose, _, psi) in &set {
                black_box(robot.ik_arm_angle(black_box(pose), black_box(*psi)));
            }
        })
    });
    g.bench_function("arm_angle_intervals", |b| {
        b.iter(|| {
            for (pose, q, _) in &set {
                black_box(robot.arm_angle_intervals(black_box(pose), configuration(q)));
            }
        })
    });
    g.bench_function("ik_with_joint_7_locked", |b| {
        b.iter(|| {
            for (pose, q, _) in &set {
                black_box(robot.ik_with(black_box(pose), q[6]));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
