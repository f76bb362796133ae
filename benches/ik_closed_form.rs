//! Closed-form IK, all solutions per call, on the same 1 000 poses for every contender
//! (fk of configurations drawn within the limits, fixed seed):
//!
//! - kinegen's generated `ik` (UR5, PUMA 560), and the Franka Panda's `ik_with(pose, q7)`
//!   (joint 7 locked at the generating configuration's value, all solutions of the other
//!   six; issue 27 — He & Liu's analytic Panda IK is compared outside CI by
//!   `benches/panda_ik/panda_ik_bench.py`);
//! - `rs-opw-kinematics` (PUMA 560 only: OPW covers spherical-wrist arms, not the UR),
//!   with parameters fitted to the same DH table and checked by forward kinematics;
//! - kinegen's numerical IK to one solution: Newton from a random start (single start)
//!   and 20 starts keeping the one nearest to the generating configuration;
//! - a 5-joint arm, the WidowX 250 (`pitch_roll`: the position, the approach in the arm's
//!   plane, the roll), closed form against one Newton solve from a random start — what
//!   its maker's SDK does (a numerical IK on the pose).
//!
//! The `ik-geo` crate is compared in its own crate, `benches/ik-geo/` (it needs CMake to
//! build NLopt, which the workspace's tests must not require).
//!
//! Before timing, a one-off report prints, per contender, how many solutions it returns,
//! how many are exact (FK within 1e-9 of the pose, measured by kinegen's fk), and how
//! often the generating configuration is among them; it panics if a contender's forward
//! kinematics differ from kinegen's (then the comparison would be meaningless).
//!
//! Run: `cargo bench --bench ik_closed_form`.

use std::f64::consts::{FRAC_PI_2, PI};
use std::hint::black_box;

#[path = "common/ik.rs"]
#[allow(dead_code)]
mod ik_common;
use ik_common::{miss, poses, same};

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen::ik::{solve, solve_nearest, IkOptions, IkTarget, MultiStart, XorShift64};
use kinegen::Kinematics;
use kinegen_robots::{Panda, Puma560, Ur5, WidowX250};
use nalgebra::Matrix4;
use rs_opw_kinematics::glam::{DMat3, DQuat, DVec3};
use rs_opw_kinematics::kinematic_traits::{Kinematics as _, Pose as OpwPose};
use rs_opw_kinematics::kinematics_impl::OPWKinematics;
use rs_opw_kinematics::parameters::opw_kinematics::Parameters;

/// Poses per contender: 1 000 when timing (`cargo bench`), 50 when CI runs the bench
/// once as a test (`cargo test --benches`, unoptimised): the checks stay, the wait goes.
fn poses_count() -> usize {
    if std::env::args().any(|a| a == "--bench") {
        1000
    } else {
        50
    }
}

/// The PUMA 560 of `robots/puma560.toml` in OPW form. Found by a search over OPW's sign
/// corrections and quarter-turn offsets against kinegen's fk, and verified by
/// [`check_opw_fk`]: `fk_kinegen(q) = fk_opw(q) · Rz(π)` (the flange frame is turned a
/// half turn about its z axis), with the same joint values.
fn opw_puma() -> OPWKinematics {
    OPWKinematics::new(Parameters {
        a1: 0.0,
        a2: -0.0203,
        b: 0.15005,
        c1: 0.0,
        c2: 0.4318,
        c3: 0.4318,
        c4: 0.0,
        offsets: [PI, FRAC_PI_2, -FRAC_PI_2, 0.0, 0.0, 0.0],
        sign_corrections: [1; 6],
        dof: 6,
    })
}

/// kinegen's tool pose → OPW's flange pose (`T · Rz(π)⁻¹`).
fn to_opw(t: &[[f64; 4]; 4]) -> OpwPose {
    let m = Matrix4::from_fn(|r, c| t[r][c]) * Matrix4::new_rotation(nalgebra::Vector3::z() * PI);
    let r = DMat3::from_cols_array(&[
        m[(0, 0)],
        m[(1, 0)],
        m[(2, 0)],
        m[(0, 1)],
        m[(1, 1)],
        m[(2, 1)],
        m[(0, 2)],
        m[(1, 2)],
        m[(2, 2)],
    ]);
    OpwPose::from_parts(
        DVec3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]),
        DQuat::from_mat3(&r),
    )
}

fn check_opw_fk(set: &[([[f64; 4]; 4], [f64; 6])]) {
    let opw = opw_puma();
    for (pose, q) in set {
        let want = to_opw(pose);
        let got = opw.forward(q);
        // Rotation matrices, not quaternion angles: acos near 1 only resolves √ε.
        let dr = DMat3::from_quat(got.rotation) - DMat3::from_quat(want.rotation);
        let d = (got.translation - want.translation).length()
            + dr.to_cols_array()
                .iter()
                .fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(
            d < 1e-9,
            "OPW's PUMA differs from kinegen's at {q:?}: {d:e}"
        );
    }
}

/// Solutions per pose, exact ones, and how often the generating q is among them.
#[derive(Default)]
struct Tally {
    solutions: usize,
    exact: usize,
    found: usize,
}

impl Tally {
    fn add<const N: usize, R: Kinematics<N>>(
        &mut self,
        robot: &R,
        pose: &[[f64; 4]; 4],
        q0: &[f64; N],
        sols: &[[f64; N]],
    ) {
        self.solutions += sols.len();
        self.exact += sols.iter().filter(|q| miss(robot, q, pose) < 1e-9).count();
        self.found += sols.iter().any(|q| same(q, q0)) as usize;
    }

    fn print(&self, name: &str) {
        println!(
            "{name:<34} {:>6} solutions ({:.2} per pose), {:>6} exact, generating q found for {}/{}",
            self.solutions,
            self.solutions as f64 / poses_count() as f64,
            self.exact,
            self.found,
            poses_count()
        );
    }
}

fn report() {
    let ur5 = Ur5::default();
    let puma = Puma560::default();
    let ur5_set = poses(&ur5, 2026, poses_count());
    let puma_set = poses(&puma, 2026, poses_count());
    check_opw_fk(&puma_set);
    let opw = opw_puma();
    let mut t = [Tally::default(), Tally::default(), Tally::default()];
    for (pose, q0) in &ur5_set {
        let s: Vec<[f64; 6]> = ur5
            .ik(pose)
            .iter()
            .filter(|b| b.exact)
            .map(|b| b.q)
            .collect();
        t[0].add(&ur5, pose, q0, &s);
    }
    for (pose, q0) in &puma_set {
        let s: Vec<[f64; 6]> = puma
            .ik(pose)
            .iter()
            .filter(|b| b.exact)
            .map(|b| b.q)
            .collect();
        t[1].add(&puma, pose, q0, &s);
        t[2].add(&puma, pose, q0, &opw.inverse(&to_opw(pose)));
    }
    t[0].print("UR5 kinegen ik (exact branches)");
    t[1].print("PUMA 560 kinegen ik (exact)");
    t[2].print("PUMA 560 rs-opw-kinematics");
    // The Panda: every branch `ik_with` returns, judged by fk (not by its own flag).
    let panda = Panda::default();
    let mut tp = Tally::default();
    let (mut flagged, mut within) = (0, 0);
    for (pose, q0) in &poses(&panda, 2026, poses_count()) {
        let sols = panda.ik_with(pose, q0[6]);
        flagged += sols.exact().count();
        let s: Vec<[f64; 7]> = sols.iter().map(|b| b.q).collect();
        // He & Liu's solver answers only inside the limits: the comparable count.
        within += s
            .iter()
            .filter(|q| (0..7).all(|i| (Panda::LIMITS[i][0]..=Panda::LIMITS[i][1]).contains(&q[i])))
            .count();
        tp.add(&panda, pose, q0, &s);
    }
    tp.print("Panda kinegen ik_with(pose, q7)");
    println!(
        "{:<34} {flagged:>6} flagged exact by ik_with, {within} within the joint limits",
        ""
    );
    let opts = IkOptions::default();
    let mut rng = XorShift64::new(7);
    let mut single = 0;
    let mut multi = 0;
    for (pose, q0) in &ur5_set {
        let target = IkTarget::Pose(kinegen::adapters::pose_isometry(pose));
        let seed = rng.configuration(&ur5.limits());
        single += solve(&ur5, &target, &seed, &opts).is_ok() as usize;
        multi += solve_nearest(&ur5, &target, q0, &opts, &MultiStart::default())
            .is_ok_and(|s| same(&s.q, q0)) as usize;
    }
    println!(
        "UR5 numerical, single random start: converged for {single}/{}",
        poses_count()
    );
    println!(
        "UR5 numerical, 20 starts (first from the generating q): that q for {multi}/{}",
        poses_count()
    );
    let widowx = WidowX250::default();
    let mut tw = Tally::default();
    let mut converged = 0;
    for (pose, q0) in &poses(&widowx, 2026, poses_count()) {
        let s: Vec<[f64; 5]> = widowx.ik(pose).exact().map(|b| b.q).collect();
        tw.add(&widowx, pose, q0, &s);
        let target = IkTarget::Pose(kinegen::adapters::pose_isometry(pose));
        let seed = rng.configuration(&widowx.limits());
        converged += solve(&widowx, &target, &seed, &opts).is_ok() as usize;
    }
    tw.print("WidowX 250 kinegen ik (exact)");
    println!(
        "WidowX 250 numerical, single random start: converged for {converged}/{}",
        poses_count()
    );
}

fn bench(c: &mut Criterion) {
    report();
    let ur5 = Ur5::default();
    let puma = Puma560::default();
    let ur5_set = poses(&ur5, 2026, poses_count());
    let puma_set = poses(&puma, 2026, poses_count());
    let opw = opw_puma();
    let opw_poses: Vec<OpwPose> = puma_set.iter().map(|(p, _)| to_opw(p)).collect();
    let mut g = c.benchmark_group("ik_all_solutions_1000_poses");
    g.bench_function("ur5_kinegen_ik", |b| {
        b.iter(|| {
            for (pose, _) in &ur5_set {
                black_box(ur5.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("puma560_kinegen_ik", |b| {
        b.iter(|| {
            for (pose, _) in &puma_set {
                black_box(puma.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("puma560_rs_opw_kinematics", |b| {
        b.iter(|| {
            for pose in &opw_poses {
                black_box(opw.inverse(black_box(pose)));
            }
        })
    });
    // Joint 7 locked at the generating configuration's value, as He & Liu's solver is
    // given it.
    let panda = Panda::default();
    let panda_set: Vec<([[f64; 4]; 4], f64)> = poses(&panda, 2026, poses_count())
        .into_iter()
        .map(|(pose, q)| (pose, q[6]))
        .collect();
    g.bench_function("panda_kinegen_ik_with_q7", |b| {
        b.iter(|| {
            for (pose, q7) in &panda_set {
                black_box(panda.ik_with(black_box(pose), black_box(*q7)));
            }
        })
    });
    let widowx = WidowX250::default();
    let widowx_set = poses(&widowx, 2026, poses_count());
    g.bench_function("widowx250_kinegen_ik", |b| {
        b.iter(|| {
            for (pose, _) in &widowx_set {
                black_box(widowx.ik(black_box(pose)));
            }
        })
    });
    g.finish();
    let targets: Vec<(IkTarget, [f64; 6], [f64; 6])> = {
        let mut rng = XorShift64::new(7);
        ur5_set
            .iter()
            .map(|(p, q0)| {
                (
                    IkTarget::Pose(kinegen::adapters::pose_isometry(p)),
                    rng.configuration(&ur5.limits()),
                    *q0,
                )
            })
            .collect()
    };
    let opts = IkOptions::default();
    let mut g = c.benchmark_group("ik_numerical_1000_poses");
    g.sample_size(10);
    g.bench_function("ur5_newton_single_start", |b| {
        b.iter(|| {
            for (t, seed, _) in &targets {
                black_box(solve(&ur5, t, seed, &opts).is_ok());
            }
        })
    });
    let widowx_targets: Vec<(IkTarget, [f64; 5])> = {
        let mut rng = XorShift64::new(7);
        widowx_set
            .iter()
            .map(|(p, _)| {
                (
                    IkTarget::Pose(kinegen::adapters::pose_isometry(p)),
                    rng.configuration(&widowx.limits()),
                )
            })
            .collect()
    };
    g.bench_function("widowx250_newton_single_start", |b| {
        b.iter(|| {
            for (t, seed) in &widowx_targets {
                black_box(solve(&widowx, t, seed, &opts).is_ok());
            }
        })
    });
    g.bench_function("ur5_newton_20_starts_nearest", |b| {
        b.iter(|| {
            for (t, _, q0) in &targets {
                black_box(solve_nearest(&ur5, t, q0, &opts, &MultiStart::default()).is_ok());
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
