//! kinegen's generated closed-form `ik` against the Robotics Toolbox for Python's
//! generated Rust IK (`DHRobot.analytic_ik().generate("rust")`, SymPy-derived, committed
//! in `generated/` by `generate.py`), all solutions per call, on the same poses: fk of
//! 1 000 configurations within the limits (seed 2026, `benches/common/ik.rs`), and 1 000
//! more with 20 % of the joints snapped to −π/2, 0 or π/2 (IKFast-style; a value outside a
//! joint's limits is not drawn), which puts many poses on or near singularities.
//!
//! Frames: the Toolbox's `models.DH.UR5()` and `models.DH.Puma560()` are kinegen's
//! `robots/ur5.toml` and `robots/puma560.toml` but for d1 (UR5: 0.089459 against UR's
//! 0.089159; PUMA 560: a 0.67183 m base height in d1). The bench measures the mapping
//! rather than assuming it: from the Toolbox's own `fkine` at the configurations of
//! `generated/fk_samples.rs` it finds one fixed transform `B` with
//! `fkine(q) = B · kinegen.fk(q)` (joint values unchanged), checks it at every sample to
//! 1e-9, and stops if there is none. The Toolbox's IK gets `B · pose`; every answer of
//! either contender is judged by kinegen's fk against kinegen's pose.
//!
//! A one-off report before timing: per contender and pose set, the solutions returned, the
//! exact ones (kinegen's fk within 1e-9 of the pose), the distinct exact ones, the wrong
//! ones (not exact) and the worst of them, the poses with no answer, and how often the
//! generating configuration is among the answers (1e-6 rad, modulo whole turns), split by
//! whether it is singular (`|det J| < 1e-9`: at a wrist singularity only q4 ± q6 is
//! determined, and any answer is one of a continuum).
//!
//! Run: `cargo bench --manifest-path benches/rtb/Cargo.toml`.

use std::f64::consts::{FRAC_PI_2, PI};
use std::hint::black_box;

#[path = "../../common/ik.rs"]
mod ik_common;
use ik_common::{miss, poses, same};

/// The Toolbox's `fkine` at a few configurations (written by `generate.py`).
#[rustfmt::skip]
#[path = "../generated/fk_samples.rs"]
mod fk_samples;

/// The Toolbox's generated code, as it writes it.
#[allow(
    clippy::all,
    dead_code,
    non_snake_case,
    unused_imports,
    unused_mut,
    unused_parens
)]
#[rustfmt::skip] // kept as the Toolbox writes it
#[path = "../generated/puma560.rs"]
mod rtb_puma560;
#[allow(
    clippy::all,
    dead_code,
    non_snake_case,
    unused_imports,
    unused_mut,
    unused_parens
)]
#[rustfmt::skip] // kept as the Toolbox writes it
#[path = "../generated/ur5.rs"]
mod rtb_ur5;

use criterion::{criterion_group, criterion_main, Criterion};
use kinegen::ik::XorShift64;
use kinegen::Kinematics;
use kinegen_robots::{Puma560, Ur5};

const POSES: usize = 1000;

/// The generated functions' `tol` (the default of the Python and C++ ones the Toolbox
/// writes; the Rust one has none): a configuration is returned when its fk is within
/// `tol` of the pose.
const RTB_TOL: f64 = 1e-6;

type Pose = [[f64; 4]; 4];
type Set = Vec<(Pose, [f64; 6])>;
/// The Toolbox's answers, and whether it said `Singular` (a branch dropped).
type RtbIk = fn(&[f64; 16]) -> (Vec<[f64; 6]>, bool);

fn mul(a: &Pose, b: &Pose) -> Pose {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// A rigid transform's inverse.
fn inv(a: &Pose) -> Pose {
    let mut r = [[0.0; 4]; 4];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = a[j][i];
        }
        r[i][3] = -(0..3).map(|k| a[k][i] * a[k][3]).sum::<f64>();
    }
    r[3][3] = 1.0;
    r
}

fn from_row_major(t: &[f64; 16]) -> Pose {
    std::array::from_fn(|i| std::array::from_fn(|j| t[4 * i + j]))
}

fn row_major(t: &Pose) -> [f64; 16] {
    std::array::from_fn(|k| t[k / 4][k % 4])
}

fn diff(a: &Pose, b: &Pose) -> f64 {
    (0..3)
        .flat_map(|i| (0..4).map(move |j| (a[i][j] - b[i][j]).abs()))
        .fold(0.0, f64::max)
}

/// The fixed base transform `B` with `fkine(q) = B · fk(q)` at every sample (1e-9), or a
/// panic saying by how much the frames cannot be reconciled.
fn base_mapping<R: Kinematics<6>>(
    name: &str,
    robot: &R,
    samples: &[([f64; 6], [f64; 16])],
) -> Pose {
    let (q0, t0) = &samples[0];
    let b = mul(&from_row_major(t0), &inv(&robot.fk(q0)));
    let worst = samples
        .iter()
        .map(|(q, t)| diff(&mul(&b, &robot.fk(q)), &from_row_major(t)))
        .fold(0.0, f64::max);
    // A tool-side transform would show here too: say so rather than go on.
    assert!(
        worst < 1e-9,
        "{name}: the Toolbox's fkine is not kinegen's fk times one fixed base transform \
         (worst {worst:e} over {} samples); the frames cannot be reconciled",
        samples.len()
    );
    let off_identity = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| (b[i][j] - if i == j { 1.0 } else { 0.0 }).abs())
        .fold(0.0, f64::max);
    println!(
        "{name}: Toolbox fkine = B · kinegen fk at {} samples (worst {worst:.1e}), B: \
         rotation max |R - I| = {off_identity:.1e}, translation [{:.6}, {:.6}, {:.6}]",
        samples.len(),
        b[0][3],
        b[1][3],
        b[2][3]
    );
    b
}

/// `count` poses of configurations within the limits with 20 % of the joints snapped to
/// one of −π/2, 0, π/2 that lies within that joint's limits (seeded).
fn snapped_poses<R: Kinematics<6>>(robot: &R, seed: u64, count: usize) -> Set {
    let limits = robot.limits();
    let mut rng = XorShift64::new(seed);
    (0..count)
        .map(|_| {
            let q: [f64; 6] = std::array::from_fn(|i| {
                let [lo, hi] = limits[i];
                if rng.next_f64() < 0.2 {
                    let inside: Vec<f64> = [-FRAC_PI_2, 0.0, FRAC_PI_2]
                        .into_iter()
                        .filter(|v| (lo..=hi).contains(v))
                        .collect();
                    inside[(rng.next_u64() % inside.len() as u64) as usize]
                } else {
                    lo + (hi - lo) * rng.next_f64()
                }
            });
            (robot.fk(&q), q)
        })
        .collect()
}

#[derive(Default)]
struct Tally {
    solutions: usize,
    exact: usize,
    distinct_exact: usize,
    wrong: usize,
    worst: f64,
    none: usize,
    found: usize,
    /// Poses whose generating configuration is singular (`|det J| < 1e-9`), and at how
    /// many of them it is among the answers.
    singular_poses: usize,
    found_singular: usize,
    /// Per joint, at how many regular poses whose generating configuration is not among
    /// the answers that joint is within 5e-3 of ±π/2 (modulo whole turns): where a
    /// derivation divides by a cosine, it shows.
    missed_at_half_turn: [usize; 6],
}

impl Tally {
    fn add<R: Kinematics<6>>(&mut self, robot: &R, sols: &[[f64; 6]], pose: &Pose, q0: &[f64; 6]) {
        self.solutions += sols.len();
        self.none += sols.is_empty() as usize;
        let mut kept: Vec<&[f64; 6]> = Vec::new();
        for q in sols {
            let m = miss(robot, q, pose);
            if m < 1e-9 {
                self.exact += 1;
                if !kept.iter().any(|k| same(k, q)) {
                    kept.push(q);
                }
            } else {
                self.wrong += 1;
                self.worst = self.worst.max(m);
            }
        }
        self.distinct_exact += kept.len();
        let found = sols.iter().any(|q| same(q, q0));
        self.found += found as usize;
        if robot.jacobian_det(q0).is_some_and(|d| d.abs() < 1e-9) {
            self.singular_poses += 1;
            self.found_singular += found as usize;
        } else if !found {
            for (n, q) in self.missed_at_half_turn.iter_mut().zip(q0) {
                *n += ((q.rem_euclid(PI) - FRAC_PI_2).abs() < 5e-3) as usize;
            }
        }
    }

    fn print(&self, label: &str) {
        let worst = if self.wrong > 0 {
            format!(" (worst {:.1e})", self.worst)
        } else {
            String::new()
        };
        println!(
            "{label} {:>5} solutions, {:>5} exact (1e-9), {:>5} distinct exact, {:>4} wrong{worst}, \
             {:>3} poses with none, generating q among them for {}/{POSES} \
             ({}/{} where it is regular, {}/{} where it is singular)",
            self.solutions,
            self.exact,
            self.distinct_exact,
            self.wrong,
            self.none,
            self.found,
            self.found - self.found_singular,
            POSES - self.singular_poses,
            self.found_singular,
            self.singular_poses
        );
        let missed = POSES - self.singular_poses + self.found_singular - self.found;
        if missed > 0 {
            println!(
                "{label} of the {missed} regular poses missed, joints 1-6 within 5e-3 of ±π/2 at: {:?}",
                self.missed_at_half_turn
            );
        }
    }
}

fn report<R: Kinematics<6>>(
    name: &str,
    robot: &R,
    ours: impl Fn(&Pose) -> Vec<[f64; 6]>,
    rtb: RtbIk,
    b: &Pose,
    set_name: &str,
    set: &Set,
) {
    let (mut k, mut r) = (Tally::default(), Tally::default());
    let mut singular = 0;
    for (pose, q0) in set {
        k.add(robot, &ours(pose), pose, q0);
        let (sols, sing) = rtb(&row_major(&mul(b, pose)));
        singular += sing as usize;
        r.add(robot, &sols, pose, q0);
    }
    k.print(&format!("{name} {set_name:<8} kinegen"));
    r.print(&format!("{name} {set_name:<8} RTB    "));
    println!(
        "{name} {set_name:<8} RTB status Singular (a branch dropped) on {singular}/{POSES} poses"
    );
}

fn rtb_ur5_ik(t: &[f64; 16]) -> (Vec<[f64; 6]>, bool) {
    let r = rtb_ur5::ikine(t, RTB_TOL);
    (r.solutions, r.status == rtb_ur5::IkStatus::Singular)
}

fn rtb_puma560_ik(t: &[f64; 16]) -> (Vec<[f64; 6]>, bool) {
    let r = rtb_puma560::ikine(t, RTB_TOL);
    (r.solutions, r.status == rtb_puma560::IkStatus::Singular)
}

fn bench(c: &mut Criterion) {
    let ur5 = Ur5::default();
    let puma = Puma560::default();
    let bu = base_mapping("UR5     ", &ur5, &fk_samples::UR5);
    let bp = base_mapping("PUMA 560", &puma, &fk_samples::PUMA560);
    let sets = [
        (
            "uniform",
            poses(&ur5, 2026, POSES),
            poses(&puma, 2026, POSES),
        ),
        (
            "snapped",
            snapped_poses(&ur5, 2026, POSES),
            snapped_poses(&puma, 2026, POSES),
        ),
    ];
    for (set_name, ur5_set, puma_set) in &sets {
        report(
            "UR5     ",
            &ur5,
            |p| ur5.ik(p).as_slice().iter().map(|b| b.q).collect(),
            rtb_ur5_ik,
            &bu,
            set_name,
            ur5_set,
        );
        report(
            "PUMA 560",
            &puma,
            |p| puma.ik(p).as_slice().iter().map(|b| b.q).collect(),
            rtb_puma560_ik,
            &bp,
            set_name,
            puma_set,
        );
    }
    for (set_name, ur5_set, puma_set) in &sets {
        let ur5_targets: Vec<[f64; 16]> = ur5_set
            .iter()
            .map(|(p, _)| row_major(&mul(&bu, p)))
            .collect();
        let puma_targets: Vec<[f64; 16]> = puma_set
            .iter()
            .map(|(p, _)| row_major(&mul(&bp, p)))
            .collect();
        let mut g = c.benchmark_group(format!("ik_all_solutions_1000_{set_name}_poses"));
        g.bench_function("ur5_kinegen_ik", |b| {
            b.iter(|| {
                for (pose, _) in ur5_set {
                    black_box(ur5.ik(black_box(pose)));
                }
            })
        });
        g.bench_function("ur5_rtb", |b| {
            b.iter(|| {
                for t in &ur5_targets {
                    black_box(rtb_ur5::ikine(black_box(t), RTB_TOL));
                }
            })
        });
        g.bench_function("puma560_kinegen_ik", |b| {
            b.iter(|| {
                for (pose, _) in puma_set {
                    black_box(puma.ik(black_box(pose)));
                }
            })
        });
        g.bench_function("puma560_rtb", |b| {
            b.iter(|| {
                for t in &puma_targets {
                    black_box(rtb_puma560::ikine(black_box(t), RTB_TOL));
                }
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
