//! A fixed workload of closed-form IK for instruction counts, which unlike timings on a
//! shared machine do not move between runs: the generated `ik` of the UR5 or the PUMA 560
//! (`kinegen-robots`), or the Panda's `ik_with(pose, q7)` with q7 of the generating
//! configuration, on the 1 000 poses of `benches/ik_closed_form.rs` (fk of configurations
//! drawn within the limits, seed 2026), 20 times over.
//!
//! Run: `cargo build --release --example ik_instructions`, then
//! `valgrind --tool=callgrind target/release/examples/ik_instructions ur5` (or `puma560`,
//! `panda`, the quartic families' `skew_shoulder` and `ur5e_wrist_offset`, `widowx250`,
//! `iiwa_arm_angle`, the general 6R's `kinova_jaco`):
//! instructions per `ik` = the total / 20 000 (the set-up adds under 1 %). Without
//! valgrind it prints the time per `ik` too (a rough figure: criterion's is the one
//! `BENCHMARKS.md` reports).

use std::hint::black_box;
use std::time::Instant;

use kinegen::Kinematics;
use kinegen_robots::{
    KinovaJaco, KukaIiwa14, Panda, Puma560, SkewShoulder, Ur5, Ur5eWristOffset, WidowX250,
};

// The bench's own poses (fk of configurations drawn within the limits, seeded).
#[path = "../benches/common/ik.rs"]
#[allow(dead_code)]
mod ik_common;

/// `ik(robot, pose, q)`: the number of solutions for `pose`, made by configuration `q`.
fn run<const N: usize, R: Kinematics<N>>(
    robot: &R,
    ik: impl Fn(&R, &[[f64; 4]; 4], &[f64; N]) -> usize,
) {
    let poses = ik_common::poses(robot, 2026, 1000);
    let start = Instant::now();
    let mut solutions = 0;
    for _ in 0..20 {
        for (pose, q) in &poses {
            solutions += ik(robot, black_box(pose), q);
        }
    }
    let ns = start.elapsed().as_nanos() as f64 / 20_000.0;
    println!("{solutions} solutions in 20 000 calls, {ns:.0} ns per ik");
}

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("ur5") | None => run(&Ur5::default(), |r, p, _| black_box(r.ik(p)).len()),
        Some("puma560") => run(&Puma560::default(), |r, p, _| black_box(r.ik(p)).len()),
        Some("panda") => run(&Panda::default(), |r, p, q| {
            black_box(r.ik_with(p, black_box(q[6]))).len()
        }),
        Some("skew_shoulder") => run(&SkewShoulder::default(), |r, p, _| black_box(r.ik(p)).len()),
        Some("ur5e_wrist_offset") => run(&Ur5eWristOffset::default(), |r, p, _| {
            black_box(r.ik(p)).len()
        }),
        // The arm angle of the generating configuration, as `benches/ik_arm_angle.rs`
        // times it (its `arm_angle` call is inside the count here: subtract it, or read
        // `ik_arm_angle`'s inclusive cost).
        Some("iiwa_arm_angle") => run(&KukaIiwa14::default(), |r, p, q| {
            black_box(r.ik_arm_angle(p, r.arm_angle(q).unwrap_or(0.0))).len()
        }),
        Some("widowx250") => run(&WidowX250::default(), |r, p, _| black_box(r.ik(p)).len()),
        Some("kinova_jaco") => run(&KinovaJaco::default(), |r, p, _| black_box(r.ik(p)).len()),
        Some(other) => {
            eprintln!(
                "unknown robot {other:?}: ur5, puma560, panda, skew_shoulder, ur5e_wrist_offset, widowx250, kinova_jaco or iiwa_arm_angle"
            );
            std::process::exit(2);
        }
    }
}
