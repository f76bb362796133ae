//! The quartic families (issue 27): all solutions per call of the generated `ik`, on 1 000
//! poses each (fk of configurations drawn within the limits, fixed seed), beside the UR5
//! (a family of quadratics) in the same run:
//!
//! - `robots/skew_shoulder.toml` — a spherical wrist after three axes in no special
//!   position: SP5 for the arm, the wrist by SP4/SP1;
//! - `robots/ur5e_wrist_offset.toml` — h2 ∥ h3 ∥ h4 with axes 5 and 6 missing each other
//!   by 5 cm: SP6 for (q1, q5);
//! - the UR5 (`three parallel, two intersecting`), for scale.
//!
//! Target: ≤ 1 µs per all-solutions call for a quartic family. A one-off check first:
//! every exact solution within 1e-10 of its pose (kinegen's fk), and how often the
//! generating configuration is among them (printed, and required for every pose).
//! Run: `cargo bench --bench ik_quartic`.

use std::hint::black_box;

#[path = "common/ik.rs"]
mod ik_common;
use ik_common::{check_solutions, poses, poses_count};

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen_robots::{SkewShoulder, Ur5, Ur5eWristOffset};

fn bench(c: &mut Criterion) {
    let n = poses_count();
    let (skew, offset, ur5) = (
        SkewShoulder::default(),
        Ur5eWristOffset::default(),
        Ur5::default(),
    );
    let skew_set = poses(&skew, 27, n);
    let offset_set = poses(&offset, 27, n);
    let ur5_set = poses(&ur5, 27, n);
    check_solutions(
        "skew_shoulder (SP5)",
        &skew,
        |p, _| skew.ik(p),
        &skew_set,
        0,
    );
    check_solutions(
        "ur5e_wrist_offset (SP6)",
        &offset,
        |p, _| offset.ik(p),
        &offset_set,
        0,
    );
    check_solutions("ur5", &ur5, |p, _| ur5.ik(p), &ur5_set, 0);
    let mut g = c.benchmark_group("ik_quartic_1000_poses");
    g.bench_function("skew_shoulder_sp5_ik", |b| {
        b.iter(|| {
            for (pose, _) in &skew_set {
                black_box(skew.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("ur5e_wrist_offset_sp6_ik", |b| {
        b.iter(|| {
            for (pose, _) in &offset_set {
                black_box(offset.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("ur5_ik", |b| {
        b.iter(|| {
            for (pose, _) in &ur5_set {
                black_box(ur5.ik(black_box(pose)));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
