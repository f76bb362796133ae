//! The general 6R (issue 28): all solutions per call of the generated `ik`, on 1 000
//! poses each (fk of configurations drawn within the limits, fixed seed), beside the UR5
//! (a family of quadratics) in the same run:
//!
//! - the Kinova Jaco 2 (60° wrist, `robots/kinova_jaco.toml`);
//! - the FANUC CRX-10iA/L (`robots/fanuc_crx10ial.toml`, from ROS-Industrial's URDF);
//! - the Kinova Gen3 with joint 7 locked at its generating value (`ik_with`);
//! - the CRX's poses moved 2 m away from its base, out of its reach (1.4 m): what a
//!   reachability map pays where the arm cannot go (no solution, and the solver must
//!   say so).
//!
//! Target: ≤ 20 µs per all-solutions call for the Jaco and the CRX. A one-off check
//! first: every exact solution within 1e-10 of its pose (kinegen's fk), the solution
//! counts, and how often the generating configuration is among them (printed; every pose
//! for the Jaco, all but the few the self-tests bound for the others).
//! Run: `cargo bench --bench ik_general`.

use std::hint::black_box;

#[path = "common/ik.rs"]
mod ik_common;
use ik_common::{check_solutions, poses, poses_count};

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen_robots::{FanucCrx10iaL, KinovaGen3, KinovaJaco, Ur5};

fn bench(c: &mut Criterion) {
    let n = poses_count();
    let (jaco, crx, gen3, ur5) = (
        KinovaJaco::default(),
        FanucCrx10iaL::default(),
        KinovaGen3,
        Ur5::default(),
    );
    let jaco_set = poses(&jaco, 28, n);
    let crx_set = poses(&crx, 28, n);
    let gen3_set = poses(&gen3, 28, n);
    let ur5_set = poses(&ur5, 28, n);
    let far_set: Vec<_> = crx_set
        .iter()
        .map(|(pose, q)| {
            let mut far = *pose;
            let r = (pose[0][3].powi(2) + pose[1][3].powi(2) + pose[2][3].powi(2)).sqrt();
            for row in far.iter_mut().take(3) {
                row[3] *= 1.0 + 2.0 / r.max(1e-3);
            }
            (far, *q)
        })
        .collect();
    assert!(
        far_set
            .iter()
            .all(|(p, _)| crx.ik(p).exact().next().is_none()),
        "a moved pose is still reached"
    );
    check_solutions(
        "kinova_jaco (general 6R)",
        &jaco,
        |p, _| jaco.ik(p),
        &jaco_set,
        0,
    );
    check_solutions(
        "fanuc_crx10ial (general 6R)",
        &crx,
        |p, _| crx.ik(p),
        &crx_set,
        1,
    );
    check_solutions(
        "kinova_gen3, joint 7 locked (general 6R)",
        &gen3,
        |p, q| gen3.ik_with(p, q[6]),
        &gen3_set,
        1,
    );
    let mut group = c.benchmark_group("ik_general");
    group.bench_function("kinova_jaco", |b| {
        b.iter(|| {
            for (pose, _) in &jaco_set {
                black_box(jaco.ik(black_box(pose)));
            }
        })
    });
    group.bench_function("fanuc_crx10ial", |b| {
        b.iter(|| {
            for (pose, _) in &crx_set {
                black_box(crx.ik(black_box(pose)));
            }
        })
    });
    group.bench_function("fanuc_crx10ial_out_of_reach", |b| {
        b.iter(|| {
            for (pose, _) in &far_set {
                black_box(crx.ik(black_box(pose)));
            }
        })
    });
    group.bench_function("kinova_gen3_joint_7_locked", |b| {
        b.iter(|| {
            for (pose, q) in &gen3_set {
                black_box(gen3.ik_with(black_box(pose), q[6]));
            }
        })
    });
    group.bench_function("ur5", |b| {
        b.iter(|| {
            for (pose, _) in &ur5_set {
                black_box(ur5.ik(black_box(pose)));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
